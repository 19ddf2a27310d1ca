#pragma once
// The tools' output files, written safely (docs/cli.md, "Outputs"):
//   - checked before any work: a run that cannot write its outputs fails at once, not
//     after minutes of rendering;
//   - written through symbolic links to their target (the link stays a link), never over
//     something that is not a regular file (a FIFO, a device, a folder), keeping an
//     existing file's permissions;
//   - all or nothing: every file of a set goes to a temporary sibling first, and only when
//     all are complete are they renamed into place;
//   - several writers of one file at once never disturb each other: each has temporaries of
//     its own (temporary_files.hpp), and the file ends up as one of them wrote it whole;
//   - nothing left behind: temporaries, and folders created for the set, are removed on
//     failure and on SIGINT, SIGTERM, SIGHUP and SIGQUIT; a run killed outright leaves its
//     temporaries, which the next run writing the same file removes.
#include <filesystem>
#include <memory>
#include <string_view>
#include <vector>

#include "image/temporary_files.hpp"

namespace penumbra {

// Whether the folders of an output path may be created (compare's --out-dir) or must exist.
enum class OutputFolders { MustExist, MayBeCreated };

// The file `path` names (through symbolic links, a dangling one too); throws InputError
// naming the path when it exists but is not a regular file, names a stream (/dev/stdout,
// /dev/fd/N, /proc/PID/fd/N), its name or path is too long for the file system, or its
// folder is missing (MustExist), not a folder or not writable.
std::filesystem::path checked_output_path(const std::filesystem::path& path,
                                          OutputFolders folders = OutputFolders::MustExist);

// A set of output files written all or nothing.
class OutputFiles {
public:
    // Checks every path (checked_output_path), before anything is written.
    explicit OutputFiles(const std::vector<std::filesystem::path>& paths,
                         OutputFolders folders = OutputFolders::MustExist);
    // Removes the temporaries, and the folders it created, of an uncommitted set.
    ~OutputFiles();
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;

    // Writes the contents of `path` (one of the constructor's) to a new temporary sibling,
    // creating its folders (MayBeCreated) and first removing stale temporaries of it.
    void write(const std::filesystem::path& path, std::string_view bytes);
    // Renames every written temporary into place.
    void commit();

private:
    struct Entry {
        std::filesystem::path requested;
        std::filesystem::path target;
        std::unique_ptr<TemporaryFile> temporary;  // written, not yet renamed
    };
    struct CreatedFolder {
        std::filesystem::path path;
        int slot = -1;  // its entry in the signal handler's list
    };
    Entry& entry(const std::filesystem::path& path);
    void create_missing_folders(const std::filesystem::path& folder);
    void remove_created_folders();

    std::vector<Entry> entries_;
    std::vector<CreatedFolder> created_folders_;
    OutputFolders folders_;
    bool committed_ = false;
};

// One output file, written like a set of one.
void write_output_file(const std::filesystem::path& path, std::string_view bytes);

}  // namespace penumbra
