// Reading a file a user named (an environment map, a settings file, a script): a regular file of a
// bounded size, checked on the descriptor before a byte is read. Opening a FIFO for reading waits
// for a writer, and /dev/zero or a sparse file of gigabytes would be read without end.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace gis {

// The file's bytes. Throws gis::Error naming `what` and the path for a missing, unreadable or
// non-regular file, or one larger than maxBytes. With `enough`, reading stops as soon as it returns
// true for the bytes read so far (a header), so a large file is not read whole for its first lines.
std::string readUserFile(const std::string& path, uint64_t maxBytes, const std::string& what,
                         const std::function<bool(const std::string&)>& enough = {});

}  // namespace gis
