#include "image/output_files.hpp"

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <string>

#include "image/temporary_files.hpp"
#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr int kMostLinkHops = 40;  // Linux's own limit (ELOOP)

[[noreturn]] void refuse(const fs::path& path, const std::string& problem) {
    throw InputError(path.string() + ": " + problem);
}

fs::path folder_of(const fs::path& file) { return file.parent_path().empty() ? fs::path(".") : file.parent_path(); }

fs::path nearest_existing_folder(fs::path folder) {
    std::error_code error;
    while (!folder.empty() && !fs::exists(folder, error)) folder = folder.parent_path();
    return folder.empty() ? fs::path(".") : folder;
}

// /dev/stdout, /dev/fd/N and /proc/PID/fd/N name a process's open streams, which may be a
// regular file (stdout redirected): replacing that file is never what was meant.
void refuse_streams(const fs::path& requested, const fs::path& file) {
    std::error_code error;
    const std::string folder = fs::weakly_canonical(folder_of(file), error).string();
    if (folder == "/dev" || folder.starts_with("/proc/")) {
        refuse(requested, "names a stream or device (" + file.string() + "), not a file; redirect the output instead");
    }
}

// The file `path` finally names: symbolic links are followed hop by hop, a dangling one too
// (its target is then created, as cp and the shell's `>` do); the link stays a link.
fs::path link_target(const fs::path& path) {
    fs::path current = path;
    for (int hop = 0; hop <= kMostLinkHops; ++hop) {
        refuse_streams(path, current);
        std::error_code error;
        if (!fs::is_symlink(fs::symlink_status(current, error))) return current;
        const fs::path next = fs::read_symlink(current, error);
        if (error) refuse(path, "cannot follow the symbolic link: " + error.message());
        current = next.is_absolute() ? next : current.parent_path() / next;
    }
    refuse(path, "too many levels of symbolic links");
}

// A name the file system cannot hold fails here, before any work, not at the rename.
void check_name_length(const fs::path& requested, const fs::path& target, const fs::path& existing_folder) {
    const long name_max = ::pathconf(existing_folder.c_str(), _PC_NAME_MAX);
    const size_t most_bytes = name_max > 0 ? static_cast<size_t>(name_max) : NAME_MAX;
    const size_t name_bytes = target.filename().native().size();
    if (name_bytes > most_bytes) {
        refuse(requested, "the file name is " + std::to_string(name_bytes) + " bytes long, more than the " +
                              std::to_string(most_bytes) + " its file system allows");
    }
    std::error_code error;
    constexpr size_t kTemporaryExtraBytes = 43;  // ".<pid>-<16 hex>.penumbra-tmp" and the leading dot
    const size_t path_bytes = fs::absolute(target, error).native().size() + kTemporaryExtraBytes;
    if (path_bytes >= PATH_MAX)
        refuse(requested, "the path is too long (at most " + std::to_string(PATH_MAX) + " bytes)");
}

}  // namespace

void write_output_file(const fs::path& path, std::string_view bytes) {
    OutputFiles output({path});
    output.write(path, bytes);
    output.commit();
}

fs::path checked_output_path(const fs::path& path, OutputFolders folders) {
    std::error_code error;
    if (path.empty()) refuse(path, "the output path is empty");
    const fs::path target = link_target(path);
    const fs::file_status status = fs::status(target, error);
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        refuse(path, "exists and is not a regular file (a folder, FIFO or device is never replaced)");
    }
    if (target.filename().empty()) refuse(path, "names a folder, not a file");
    fs::path folder = folder_of(target);
    if (!fs::exists(folder, error)) {
        if (folders == OutputFolders::MustExist) refuse(path, "the folder " + folder.string() + " does not exist");
        folder = nearest_existing_folder(folder);
    }
    if (!fs::is_directory(folder, error)) refuse(path, folder.string() + " is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) refuse(path, "the folder " + folder.string() + " is not writable");
    check_name_length(path, target, folder);
    return target;
}

OutputFiles::OutputFiles(const std::vector<fs::path>& paths, OutputFolders folders) : folders_(folders) {
    for (const fs::path& path : paths) entries_.push_back({path, checked_output_path(path, folders), nullptr});
}

OutputFiles::~OutputFiles() {
    if (committed_) return;
    for (Entry& file : entries_) file.temporary.reset();  // removes it
    remove_created_folders();
}

OutputFiles::Entry& OutputFiles::entry(const fs::path& path) {
    const auto found =
        std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.requested == path; });
    if (found == entries_.end()) throw UsageError(path.string() + ": not among the declared output files");
    return *found;
}

void OutputFiles::write(const fs::path& path, std::string_view bytes) {
    Entry& file = entry(path);
    if (folders_ == OutputFolders::MayBeCreated) create_missing_folders(folder_of(file.target));
    remove_stale_temporaries(file.target);
    file.temporary = std::make_unique<TemporaryFile>(file.target, file.requested);
    file.temporary->write(bytes);
}

void OutputFiles::commit() {
    for (Entry& file : entries_) {
        if (!file.temporary) continue;
        std::error_code error;
        // Keep an existing file's permissions (a new one gets the umask's, as any new file).
        const fs::file_status existing = fs::status(file.target, error);
        if (fs::is_regular_file(existing)) fs::permissions(file.temporary->path(), existing.permissions(), error);
        file.temporary->rename_to(file.target);  // on failure the rest are removed
        file.temporary.reset();
    }
    for (const CreatedFolder& folder : created_folders_) unregister_created_folder(folder.slot);
    created_folders_.clear();
    committed_ = true;
}

// Each missing folder from the outermost in, remembered so that a failed or interrupted set
// leaves no folder it made.
void OutputFiles::create_missing_folders(const fs::path& folder) {
    std::vector<fs::path> missing;
    std::error_code error;
    for (fs::path level = folder; !level.empty() && !fs::exists(level, error); level = level.parent_path()) {
        missing.push_back(level);
    }
    for (auto level = missing.rbegin(); level != missing.rend(); ++level) {
        const bool created = fs::create_directory(*level, error);
        if (error) refuse(*level, "cannot create the folder: " + error.message());
        if (created) created_folders_.push_back({*level, register_created_folder(*level)});
    }
}

void OutputFiles::remove_created_folders() {
    for (auto folder = created_folders_.rbegin(); folder != created_folders_.rend(); ++folder) {
        ::rmdir(folder->path.c_str());  // only when empty: never what someone else put there
        unregister_created_folder(folder->slot);
    }
    created_folders_.clear();
}

}  // namespace penumbra
