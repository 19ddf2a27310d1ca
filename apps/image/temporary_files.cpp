#include "image/temporary_files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <optional>
#include <random>

#include "penumbra/errors.hpp"

namespace penumbra {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kSuffix = ".penumbra-tmp";
constexpr size_t kRandomHexDigits = 16;

// ---------------------------------------------------------------- signal cleanup
// Temporaries and created folders, readable from a signal handler: fixed slots of plain
// characters, each published by an atomic flag once its path is in place.
constexpr size_t kSlotCount = 64;
constexpr size_t kPathBytes = 4096;

struct CleanupSlot {
    std::atomic<bool> used{false};
    bool is_folder = false;
    std::array<char, kPathBytes> path{};
};
std::array<CleanupSlot, kSlotCount> g_cleanup;

extern "C" void remove_temporaries_and_reraise(int signal_number) {
    for (CleanupSlot& slot : g_cleanup) {
        if (slot.used.load() && !slot.is_folder) ::unlink(slot.path.data());  // async-signal-safe
    }
    // Folders last, the later-created (deeper) first; rmdir leaves a non-empty one.
    for (size_t i = kSlotCount; i-- > 0;) {
        if (g_cleanup[i].used.load() && g_cleanup[i].is_folder) ::rmdir(g_cleanup[i].path.data());
    }
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
}

// Installed wherever a signal still has its default action, checked at each registration
// (not once per process): a signal the process ignores (a background job's SIGINT) stays
// ignored, and one reset to its default later (a forked child) gets the cleanup again.
void install_signal_cleanup() {
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    sigemptyset(&action.sa_mask);
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
        struct sigaction previous {};
        if (sigaction(signal_number, nullptr, &previous) == 0 && previous.sa_handler == SIG_DFL) {
            sigaction(signal_number, &action, nullptr);
        }
    }
}

// The slot now holding `path`, or -1 when all are taken or the path is too long (a
// temporary is then only cleaned up by the next run, a folder stays).
int register_cleanup(const fs::path& path, bool is_folder) {
    install_signal_cleanup();
    const std::string& text = path.native();
    if (text.size() >= kPathBytes) return -1;
    for (size_t i = 0; i < kSlotCount; ++i) {
        CleanupSlot& slot = g_cleanup[i];
        if (slot.used.load()) continue;
        std::copy(text.begin(), text.end(), slot.path.begin());
        slot.path[text.size()] = '\0';
        slot.is_folder = is_folder;
        bool expected = false;
        if (slot.used.compare_exchange_strong(expected, true)) return static_cast<int>(i);
    }
    return -1;
}

void unregister_cleanup(int slot) {
    if (slot >= 0) g_cleanup[static_cast<size_t>(slot)].used.store(false);
}

// ---------------------------------------------------------------- names

// `.<name>.`, the name cut (at a UTF-8 character boundary) so that the whole temporary name
// fits the file system's usual NAME_MAX.
std::string temporary_prefix(const fs::path& target) {
    constexpr size_t kLongestPid = 10;
    constexpr size_t kRoom = NAME_MAX - 2 - kLongestPid - 1 - kRandomHexDigits - kSuffix.size();
    std::string name = target.filename().string();
    if (name.size() > kRoom) {
        size_t cut = kRoom;
        while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
        name.resize(cut);
    }
    return "." + name + ".";
}

std::string random_hex() {
    static std::mt19937_64 generator{std::random_device{}()};
    char text[kRandomHexDigits + 1];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(generator()));
    return text;
}

// The pid in `filename` when it is `<prefix><pid>-<16 hex digits>.penumbra-tmp`.
std::optional<pid_t> temporary_owner(const std::string& filename, const std::string& prefix) {
    if (filename.size() <= prefix.size() + kSuffix.size() || !filename.starts_with(prefix) ||
        !filename.ends_with(kSuffix)) {
        return std::nullopt;
    }
    const std::string middle = filename.substr(prefix.size(), filename.size() - prefix.size() - kSuffix.size());
    const size_t dash = middle.find('-');
    if (dash == 0 || dash == std::string::npos || dash > 10 || middle.size() - dash - 1 != kRandomHexDigits) {
        return std::nullopt;
    }
    const auto is_digit = [](char c) { return c >= '0' && c <= '9'; };
    const auto is_hex = [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); };
    if (!std::all_of(middle.begin(), middle.begin() + dash, is_digit) ||
        !std::all_of(middle.begin() + dash + 1, middle.end(), is_hex)) {
        return std::nullopt;
    }
    const long long pid = std::stoll(middle.substr(0, dash));
    if (pid <= 0 || pid > INT_MAX) return std::nullopt;
    return static_cast<pid_t>(pid);
}

bool process_is_alive(pid_t pid) { return ::kill(pid, 0) == 0 || errno == EPERM; }

// Removes the regular file `path` if nobody holds its lock.
void remove_if_unlocked(const fs::path& path) {
    const int descriptor = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (descriptor < 0) return;
    struct stat info {};
    if (::fstat(descriptor, &info) == 0 && S_ISREG(info.st_mode) && ::flock(descriptor, LOCK_EX | LOCK_NB) == 0) {
        ::unlink(path.c_str());
    }
    ::close(descriptor);
}

[[noreturn]] void refuse(const fs::path& label, const std::string& problem) {
    throw InputError(label.string() + ": " + problem);
}

}  // namespace

TemporaryFile::TemporaryFile(const fs::path& target, const fs::path& label) : label_(label) {
    const std::string stem = temporary_prefix(target) + std::to_string(::getpid()) + "-";
    for (int attempt = 0; attempt < 8 && write_descriptor_ < 0; ++attempt) {
        path_ = target.parent_path() / (stem + random_hex() + std::string(kSuffix));
        // O_EXCL | O_NOFOLLOW: never an existing file, never through a link planted here.
        write_descriptor_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (write_descriptor_ < 0 && errno != EEXIST) break;
    }
    if (write_descriptor_ < 0) refuse(label_, "cannot create " + path_.string() + ": " + std::strerror(errno));
    slot_ = register_cleanup(path_, false);
    // Until this lock is taken, the pid in the name (alive) is what keeps others off it.
    lock_descriptor_ = ::open(path_.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (lock_descriptor_ >= 0) ::flock(lock_descriptor_, LOCK_EX | LOCK_NB);
}

TemporaryFile::~TemporaryFile() {
    if (write_descriptor_ >= 0) ::close(write_descriptor_);
    if (!renamed_) ::unlink(path_.c_str());
    unregister_cleanup(slot_);
    if (lock_descriptor_ >= 0) ::close(lock_descriptor_);
}

void TemporaryFile::write(std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t written = ::write(write_descriptor_, bytes.data(), bytes.size());
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) refuse(label_, std::string("writing failed: ") + std::strerror(errno));
        bytes.remove_prefix(static_cast<size_t>(written));
    }
}

void TemporaryFile::rename_to(const fs::path& target) {
    const int descriptor = write_descriptor_;
    write_descriptor_ = -1;
    if (::close(descriptor) != 0) refuse(label_, std::string("writing failed: ") + std::strerror(errno));
    if (::rename(path_.c_str(), target.c_str()) != 0)
        refuse(label_, std::string("cannot write: ") + std::strerror(errno));
    renamed_ = true;
}

void remove_stale_temporaries(const fs::path& target) {
    const std::string prefix = temporary_prefix(target);
    const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code error;
    for (fs::directory_iterator entry(folder, error), end; !error && entry != end; entry.increment(error)) {
        const std::optional<pid_t> owner = temporary_owner(entry->path().filename().string(), prefix);
        if (owner && !process_is_alive(*owner)) remove_if_unlocked(entry->path());
    }
}

bool is_temporary_of(const fs::path& target, const std::string& filename) {
    return temporary_owner(filename, temporary_prefix(target)).has_value();
}

int register_created_folder(const fs::path& folder) { return register_cleanup(folder, true); }

void unregister_created_folder(int slot) { unregister_cleanup(slot); }

}  // namespace penumbra
