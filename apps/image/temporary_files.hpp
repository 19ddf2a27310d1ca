#pragma once
// The temporaries that output files are written to before they are renamed into place
// (output_files.hpp). Several processes may write the same output at once, so:
//   - every temporary has a name of its own, `.<name>.<pid>-<random>.penumbra-tmp` (the name
//     shortened when needed, so that a target name the file system accepts always has a
//     temporary), created exclusively;
//   - its writer holds a lock on it (flock) for as long as it lives, so a temporary is
//     stale only when its owning process has gone AND nobody holds its lock (the lock also
//     covers a writer in another PID namespace whose pid means nothing here);
//   - the next writer of the same target removes stale ones and never a live one's;
//   - SIGINT, SIGTERM, SIGHUP and SIGQUIT remove every temporary (and every folder created
//     for an output) of the process before it ends.
#include <filesystem>
#include <string>
#include <string_view>

namespace penumbra {

// One temporary sibling of an output file, created, open and locked; removed by the
// destructor unless it was renamed into place.
class TemporaryFile {
public:
    // Creates it next to `target`; `label` (the path the user gave) starts error messages.
    // Throws InputError when it cannot be created.
    TemporaryFile(const std::filesystem::path& target, const std::filesystem::path& label);
    ~TemporaryFile();
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;

    // Appends `bytes`; throws InputError naming the label on a write error.
    void write(std::string_view bytes);
    // Completes the file and renames it over `target`; throws InputError on failure (the
    // temporary is then still removed by the destructor).
    void rename_to(const std::filesystem::path& target);

    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
    std::filesystem::path label_;
    int write_descriptor_ = -1;
    int lock_descriptor_ = -1;  // a separate open file: its lock outlives the write descriptor
    int slot_ = -1;             // its entry in the signal handler's list
    bool renamed_ = false;
};

// Removes the temporaries of `target` that killed writers left behind: those whose owning
// process is gone and whose lock nobody holds. Never fails (a temporary that cannot be
// removed stays).
void remove_stale_temporaries(const std::filesystem::path& target);

// Whether `filename` is the name of a temporary of `target` (of any process).
bool is_temporary_of(const std::filesystem::path& target, const std::string& filename);

// A folder created for outputs, removed (if still empty) on the signals above; -1 when the
// signal handler's list is full. unregister_created_folder() once it is kept or removed.
int register_created_folder(const std::filesystem::path& folder);
void unregister_created_folder(int slot);

}  // namespace penumbra
