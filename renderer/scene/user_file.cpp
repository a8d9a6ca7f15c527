#include "user_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "error.h"

namespace gis {

namespace {
// Closes the descriptor on every path out.
struct Descriptor {
    int fd;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};
}  // namespace

std::string readUserFile(const std::string& path, uint64_t maxBytes, const std::string& what,
                         const std::function<bool(const std::string&)>& enough) {
    const std::string named = what + " '" + path + "'";
    // O_NONBLOCK: the open itself must not wait for a FIFO's writer; the check is on the
    // descriptor, so the file cannot be swapped between the check and the read.
    const Descriptor d{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (d.fd < 0)
        throw Error(errno == ENOENT ? named + " does not exist" : named + ": cannot read (" + std::strerror(errno) + ")");
    struct stat st {};
    if (::fstat(d.fd, &st) != 0) throw Error(named + ": cannot read (" + std::strerror(errno) + ")");
    if (!S_ISREG(st.st_mode)) throw Error(named + " is not a regular file");
    if (uint64_t(st.st_size) > maxBytes)
        throw Error(named + " is too large (" + std::to_string(st.st_size) + " bytes, the limit is " +
                    std::to_string(maxBytes) + ")");
    // The size may change while it is read: the limit holds for what is read, not only the stat.
    std::string bytes;
    size_t chunk = 64 * 1024;
    for (;;) {
        const size_t at = bytes.size();
        bytes.resize(at + chunk);
        const ssize_t got = ::read(d.fd, bytes.data() + at, chunk);
        if (got < 0 && errno == EINTR) {
            bytes.resize(at);
            continue;
        }
        if (got < 0) throw Error(named + ": cannot read (" + std::strerror(errno) + ")");
        bytes.resize(at + size_t(got));
        if (bytes.size() > maxBytes)
            throw Error(named + " is too large (more than " + std::to_string(maxBytes) + " bytes)");
        if (got == 0 || (enough && enough(bytes))) return bytes;
        chunk = std::min<size_t>(chunk * 2, size_t(64) << 20);  // a long header is read in few steps
    }
}

}  // namespace gis
