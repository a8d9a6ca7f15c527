// The one way the program writes a file. Every output (images, EXR, glTF + bin, JSON, CSV,
// charts, settings, screenshots, bench records) goes through here:
//   1. a temporary file is created beside the target with O_CREAT|O_EXCL|O_NOFOLLOW, mode 0600,
//      under a random name (mkostemp), so no other user can predict, pre-create or redirect it;
//   2. every write is checked; the data is fsync'ed before the rename;
//   3. the temporary gets the target's mode (an existing file's, else 0666 & ~umask) and is
//      renamed over the target, so a reader sees the old file or the new one, never a part.
// Any failure leaves the old target untouched, removes the temporary and throws gis::Error
// naming the target and the OS reason (strerror). SIGINT/SIGTERM/SIGHUP remove the temporaries
// before the process dies; SIGXFSZ is ignored so a file-size limit is an error (EFBIG), not a kill.
// Lives in gis_scene (no GL) so the glTF writer and every layer above can use it.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace gis {

// SIGXFSZ -> ignored, unless the process already ignores or handles it. main() calls it first;
// the writers call it too, so a test or a library user gets the same behaviour.
void ignoreFileSizeSignal();

// One file being written. Destroyed without commit(): the temporary is removed, the target kept.
class AtomicFile {
public:
    explicit AtomicFile(const std::string& path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    void write(const void* data, size_t bytes);  // throws on the first failure
    void write(const std::string& bytes) { write(bytes.data(), bytes.size()); }
    void sync();    // fsync and close: the bytes are on disk under the temporary name
    void commit();  // sync() if not done, then rename over the target

    const std::string& path() const { return path_; }
    const std::string& tempPath() const { return tmp_; }

private:
    [[noreturn]] void fail(const std::string& what, int err);
    std::string path_, tmp_;
    int fd_ = -1;
    int slot_ = -1;  // in the signal handlers' table
    bool committed_ = false;
};

// Writes `bytes` to `path` as above.
void writeFileAtomically(const std::string& path, const std::string& bytes);

// A set of files that appear together or not at all (a glTF and its .bin, a merge's tables and
// charts): every temporary is written and synced first, then all are renamed. A failure while
// writing (full disk, size limit) changes none of the targets.
void writeFilesAtomically(const std::vector<std::pair<std::string, std::string>>& files);

// Creates and removes a temporary beside `path`: fails early (before minutes of rendering)
// with the OS reason when the target's directory cannot take a new file.
void checkCanCreateBeside(const std::string& path);

// The same file (device and inode) for two existing paths; false when either does not exist.
bool sameFile(const std::string& a, const std::string& b);

}  // namespace gis
