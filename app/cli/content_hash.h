// SHA-256 (OpenSSL libcrypto) for content ids: bench sweep jobs, their cached references and the
// checksums that let `bench --merge` tell a finished result file from a truncated or damaged one.
#pragma once

#include <string>

namespace gis {

class Sha256 {
public:
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;
    void update(const void* data, size_t size);
    void update(const std::string& text) { update(text.data(), text.size()); }
    // Adds a file's bytes; throws gis::Error naming the file when it cannot be read.
    void updateFile(const std::string& path);
    std::string hex();  // lowercase, 64 digits; the object is spent afterwards

private:
    void* ctx_;  // EVP_MD_CTX
};

std::string sha256Hex(const std::string& bytes);
std::string sha256File(const std::string& path);

}  // namespace gis
