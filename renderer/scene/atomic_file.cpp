#include "atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>

#include "scene/scene.h"

namespace gis {

namespace {

// The temporaries that exist now, for the signal handlers: fixed buffers and flags, because a
// handler may only use async-signal-safe calls (unlink, sigaction, raise).
constexpr int kSlots = 16;
char gSlotPath[kSlots][4096];
volatile sig_atomic_t gSlotActive[kSlots] = {};
int gActiveCount = 0;  // under gMutex
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction gOldActions[3];
std::mutex gMutex;

extern "C" void removeTemporariesAndReraise(int sig) {
    for (int i = 0; i < kSlots; ++i)
        if (gSlotActive[i]) {
            ::unlink(gSlotPath[i]);
            gSlotActive[i] = 0;
        }
    for (size_t i = 0; i < 3; ++i)
        if (kCleanupSignals[i] == sig) ::sigaction(sig, &gOldActions[i], nullptr);
    ::raise(sig);  // now with the previous disposition (by default: terminate)
}

// Installed while at least one temporary exists, and only where the signal would kill the
// process: one the caller ignores (nohup) stays ignored, one it handles (a window's graceful
// quit) lets the write finish. SIGKILL cannot be caught: it leaves a temporary, never a partial target.
void installHandlers() {
    struct sigaction sa {};
    sa.sa_handler = removeTemporariesAndReraise;
    sigemptyset(&sa.sa_mask);
    for (size_t i = 0; i < 3; ++i) {
        ::sigaction(kCleanupSignals[i], &sa, &gOldActions[i]);
        const bool wasDefault = !(gOldActions[i].sa_flags & SA_SIGINFO) && gOldActions[i].sa_handler == SIG_DFL;
        if (!wasDefault) ::sigaction(kCleanupSignals[i], &gOldActions[i], nullptr);
    }
}

void restoreHandlers() {
    for (size_t i = 0; i < 3; ++i) ::sigaction(kCleanupSignals[i], &gOldActions[i], nullptr);
}

// Returns the slot armed for `tmp`, or -1 (too long a path, or every slot taken): such a
// temporary is still removed by the destructor, only not by a signal.
int armSlot(const std::string& tmp) {
    std::lock_guard<std::mutex> lock(gMutex);
    if (tmp.size() >= sizeof gSlotPath[0]) return -1;
    for (int i = 0; i < kSlots; ++i) {
        if (gSlotActive[i]) continue;
        std::memcpy(gSlotPath[i], tmp.c_str(), tmp.size() + 1);
        if (gActiveCount++ == 0) installHandlers();
        gSlotActive[i] = 1;
        return i;
    }
    return -1;
}

void disarmSlot(int slot) {
    if (slot < 0) return;
    std::lock_guard<std::mutex> lock(gMutex);
    gSlotActive[slot] = 0;
    if (--gActiveCount == 0) restoreHandlers();
}

mode_t targetMode(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 07777;
    static const mode_t umaskNow = [] {
        const mode_t m = ::umask(0);
        ::umask(m);
        return m;
    }();
    return 0666 & ~umaskNow;
}

std::string directoryOf(const std::string& path) {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    return dir.empty() ? std::string(".") : dir.string();
}

// The directory entry of a rename is durable only once the directory itself is synced.
void syncDirectory(const std::string& dir) {
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);  // the rename is done; a file system that cannot sync directories still has it
    ::close(fd);
}

}  // namespace

void ignoreFileSizeSignal() {
    static std::once_flag once;
    std::call_once(once, [] {
        struct sigaction old {};
        if (::sigaction(SIGXFSZ, nullptr, &old) != 0) return;
        if ((old.sa_flags & SA_SIGINFO) || old.sa_handler != SIG_DFL) return;
        struct sigaction ign {};
        ign.sa_handler = SIG_IGN;
        sigemptyset(&ign.sa_mask);
        ::sigaction(SIGXFSZ, &ign, nullptr);
    });
}

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
    ignoreFileSizeSignal();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a directory");
    const std::string dir = directoryOf(path);
    if (!std::filesystem::is_directory(dir, ec)) throw Error(path + ": directory " + dir + " does not exist");
    std::string name = path + ".tmp.XXXXXX";
    // mkostemp: O_CREAT | O_EXCL with a random suffix and mode 0600 -- never an existing file or
    // a symlink someone planted, and unreadable to others until it is complete and renamed.
    fd_ = ::mkostemp(name.data(), O_CLOEXEC);
    if (fd_ < 0) {
        const int err = errno;
        throw Error(path + ": cannot create a temporary file in " + dir + ": " + std::strerror(err));
    }
    tmp_ = name;
    slot_ = armSlot(tmp_);
}

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_ && !tmp_.empty()) ::unlink(tmp_.c_str());
    disarmSlot(slot_);
}

void AtomicFile::fail(const std::string& what, int err) {
    throw Error(path_ + ": " + what + ": " + std::strerror(err ? err : EIO));
}

void AtomicFile::write(const void* data, size_t bytes) {
    if (fd_ < 0) throw Error(path_ + ": written after it was closed");
    const char* p = static_cast<const char*>(data);
    while (bytes > 0) {
        const ssize_t n = ::write(fd_, p, bytes);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) fail("cannot write", n < 0 ? errno : ENOSPC);
        p += n;
        bytes -= size_t(n);
    }
}

void AtomicFile::sync() {
    if (fd_ < 0) return;
    // fsync reports what write could not (NFS, quotas, delayed allocation on a full disk).
    if (::fsync(fd_) != 0 && errno != EINVAL) fail("cannot write", errno);
    if (::fchmod(fd_, targetMode(path_)) != 0) fail("cannot set the file's mode", errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0 && errno != EINTR) fail("cannot write", errno);
}

void AtomicFile::commit() {
    sync();
    if (committed_) return;
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) fail("cannot rename the temporary file over it", errno);
    committed_ = true;
    syncDirectory(directoryOf(path_));
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
    AtomicFile f(path);
    f.write(bytes);
    f.commit();
}

void writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files) {
    std::vector<std::unique_ptr<AtomicFile>> staged;
    for (const auto& [path, bytes] : files) {
        staged.push_back(std::make_unique<AtomicFile>(path));
        staged.back()->write(bytes);
        staged.back()->sync();
    }
    for (auto& f : staged) f->commit();
}

void checkCanCreateBeside(const std::string& path) {
    AtomicFile probe(path);  // throws with the reason; the destructor removes the temporary
}

bool sameFile(const std::string& a, const std::string& b) {
    struct stat sa {}, sb {};
    if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
    return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

}  // namespace gis
