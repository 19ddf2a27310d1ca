#pragma once
// The tools' output files, written safely (docs/cli.md, "Outputs"):
//   - checked before any work: a run that cannot write its outputs fails at once, not
//     after minutes of rendering;
//   - written through symbolic links to their target (the link stays a link), never over
//     something that is not a regular file (a FIFO, a device, a folder), keeping an
//     existing file's permissions;
//   - all or nothing: every file of a set goes to a temporary sibling first, and only when
//     all are complete are they renamed into place;
//   - nothing left behind: temporaries are removed on failure and on SIGINT, SIGTERM and
//     SIGHUP; a run killed outright leaves `.<name>.penumbra-tmp`, which the next run
//     writing the same file replaces.
#include <filesystem>
#include <string_view>
#include <vector>

namespace penumbra {

// Whether the folders of an output path may be created (compare's --out-dir) or must exist.
enum class OutputFolders { MustExist, MayBeCreated };

// The file `path` names (through symbolic links); throws InputError naming the path when it
// exists but is not a regular file, or when its folder is missing (MustExist), not a folder
// or not writable.
std::filesystem::path checked_output_path(const std::filesystem::path& path,
                                          OutputFolders folders = OutputFolders::MustExist);

// A set of output files written all or nothing.
class OutputFiles {
public:
    // Checks every path (checked_output_path), before anything is written.
    explicit OutputFiles(const std::vector<std::filesystem::path>& paths,
                         OutputFolders folders = OutputFolders::MustExist);
    // Removes the temporaries of an uncommitted set.
    ~OutputFiles();
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;

    // Writes the contents of `path` (one of the constructor's) to its temporary sibling.
    void write(const std::filesystem::path& path, std::string_view bytes);
    // Renames every written temporary into place.
    void commit();

private:
    struct Entry {
        std::filesystem::path requested;
        std::filesystem::path target;
        std::filesystem::path temporary;
        bool written = false;
        int slot = -1;  // its entry in the signal handler's list of temporaries
    };
    Entry& entry(const std::filesystem::path& path);
    void remove_temporaries();

    std::vector<Entry> entries_;
    OutputFolders folders_;
    bool committed_ = false;
};

// One output file, written like a set of one.
void write_output_file(const std::filesystem::path& path, std::string_view bytes);

// The temporary sibling of an output file.
std::filesystem::path temporary_output_path(const std::filesystem::path& target);

}  // namespace penumbra
