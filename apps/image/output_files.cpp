#include "image/output_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>
#include <string>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------- signal cleanup
// Temporaries in progress, readable from a signal handler: fixed slots of plain characters,
// each published by an atomic flag once its path is in place.
constexpr size_t kSlotCount = 64;
constexpr size_t kPathBytes = 4096;

struct TemporarySlot {
    std::atomic<bool> used{false};
    std::array<char, kPathBytes> path{};
};
std::array<TemporarySlot, kSlotCount> g_temporaries;

extern "C" void remove_temporaries_and_reraise(int signal_number) {
    for (TemporarySlot& slot : g_temporaries) {
        if (slot.used.load()) ::unlink(slot.path.data());  // async-signal-safe
    }
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

// Installed once, and only where nobody else handles these signals.
void install_signal_cleanup() {
    static std::once_flag once;
    std::call_once(once, [] {
        struct sigaction action {};
        action.sa_handler = remove_temporaries_and_reraise;
        sigemptyset(&action.sa_mask);
        for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
            struct sigaction previous {};
            if (sigaction(signal_number, nullptr, &previous) == 0 && previous.sa_handler == SIG_DFL) {
                sigaction(signal_number, &action, nullptr);
            }
        }
    });
}

// The slot now holding `path`, or -1 when all are taken or the path is too long (the file is
// then only cleaned up by the next run).
int register_temporary(const fs::path& path) {
    install_signal_cleanup();
    const std::string& text = path.native();
    if (text.size() >= kPathBytes) return -1;
    for (size_t i = 0; i < kSlotCount; ++i) {
        TemporarySlot& slot = g_temporaries[i];
        if (slot.used.load()) continue;
        std::copy(text.begin(), text.end(), slot.path.begin());
        slot.path[text.size()] = '\0';
        bool expected = false;
        if (slot.used.compare_exchange_strong(expected, true)) return static_cast<int>(i);
    }
    return -1;
}

void unregister_temporary(int slot) {
    if (slot >= 0) g_temporaries[static_cast<size_t>(slot)].used.store(false);
}

// ---------------------------------------------------------------- checks

fs::path nearest_existing_folder(fs::path folder) {
    std::error_code error;
    while (!folder.empty() && !fs::exists(folder, error)) folder = folder.parent_path();
    return folder.empty() ? fs::path(".") : folder;
}

[[noreturn]] void refuse(const fs::path& path, const std::string& problem) {
    throw InputError(path.string() + ": " + problem);
}

void write_all(int descriptor, std::string_view bytes, const fs::path& requested) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(descriptor, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) refuse(requested, std::string("writing failed: ") + std::strerror(errno));
        bytes.remove_prefix(static_cast<size_t>(written));
    }
}

}  // namespace

void write_output_file(const fs::path& path, std::string_view bytes) {
    OutputFiles output({path});
    output.write(path, bytes);
    output.commit();
}

fs::path temporary_output_path(const fs::path& target) {
    return target.parent_path() / ("." + target.filename().string() + ".penumbra-tmp");
}

fs::path checked_output_path(const fs::path& path, OutputFolders folders) {
    std::error_code error;
    if (path.empty()) refuse(path, "the output path is empty");
    fs::path target = path;
    if (fs::is_symlink(fs::symlink_status(path, error))) {
        target = fs::weakly_canonical(path, error);  // the link's target; the link stays
        if (error) refuse(path, "cannot follow the symbolic link: " + error.message());
    }
    const fs::file_status status = fs::status(target, error);
    if (fs::exists(status) && !fs::is_regular_file(status)) {
        refuse(path, "exists and is not a regular file (a folder, FIFO or device is never replaced)");
    }
    if (target.filename().empty()) refuse(path, "names a folder, not a file");
    fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::exists(folder, error)) {
        if (folders == OutputFolders::MustExist) refuse(path, "the folder " + folder.string() + " does not exist");
        folder = nearest_existing_folder(folder);
    }
    if (!fs::is_directory(folder, error)) refuse(path, folder.string() + " is not a folder");
    if (::access(folder.c_str(), W_OK | X_OK) != 0) refuse(path, "the folder " + folder.string() + " is not writable");
    return target;
}

OutputFiles::OutputFiles(const std::vector<fs::path>& paths, OutputFolders folders) : folders_(folders) {
    for (const fs::path& path : paths) {
        const fs::path target = checked_output_path(path, folders);
        entries_.push_back({path, target, temporary_output_path(target), false});
    }
}

OutputFiles::~OutputFiles() {
    if (!committed_) remove_temporaries();
}

OutputFiles::Entry& OutputFiles::entry(const fs::path& path) {
    const auto found =
        std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.requested == path; });
    if (found == entries_.end()) throw UsageError(path.string() + ": not among the declared output files");
    return *found;
}

void OutputFiles::write(const fs::path& path, std::string_view bytes) {
    Entry& file = entry(path);
    std::error_code error;
    if (folders_ == OutputFolders::MayBeCreated) fs::create_directories(file.target.parent_path(), error);
    ::unlink(file.temporary.c_str());  // a leftover of a killed run
    // O_EXCL | O_NOFOLLOW: a link planted under the temporary's name is not written through.
    const int descriptor = ::open(file.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (descriptor < 0) refuse(path, "cannot create " + file.temporary.string() + ": " + std::strerror(errno));
    file.slot = register_temporary(file.temporary);
    file.written = true;
    try {
        write_all(descriptor, bytes, path);
    } catch (...) {
        ::close(descriptor);
        throw;  // the destructor removes the temporary
    }
    if (::close(descriptor) != 0) refuse(path, std::string("writing failed: ") + std::strerror(errno));
}

void OutputFiles::commit() {
    for (Entry& file : entries_) {
        if (!file.written) continue;
        std::error_code error;
        // Keep an existing file's permissions (a new one gets the umask's, as any new file).
        const fs::file_status existing = fs::status(file.target, error);
        if (fs::is_regular_file(existing)) fs::permissions(file.temporary, existing.permissions(), error);
        fs::rename(file.temporary, file.target, error);
        if (error) refuse(file.requested, "cannot write: " + error.message());  // the rest are removed
        unregister_temporary(file.slot);
        file.written = false;
    }
    committed_ = true;
}

void OutputFiles::remove_temporaries() {
    for (Entry& file : entries_) {
        if (!file.written) continue;
        ::unlink(file.temporary.c_str());
        unregister_temporary(file.slot);
        file.written = false;
    }
}

}  // namespace penumbra
