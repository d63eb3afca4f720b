#include <openssl/evp.h>

#include <array>
#include <cstdio>

#include "io/dataset_error.hpp"
#include "io/provenance.hpp"

namespace grip::io {

std::string job_id(const std::string& job_text, std::uint64_t seed) {
  // The seed enters as its decimal text after a NUL, which no job text contains.
  const std::string seed_text = std::to_string(seed);
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  EVP_MD_CTX* context = EVP_MD_CTX_new();
  const bool ok = context != nullptr && EVP_DigestInit_ex(context, EVP_sha256(), nullptr) == 1 &&
                  EVP_DigestUpdate(context, job_text.data(), job_text.size()) == 1 &&
                  EVP_DigestUpdate(context, "\0", 1) == 1 &&
                  EVP_DigestUpdate(context, seed_text.data(), seed_text.size()) == 1 &&
                  EVP_DigestFinal_ex(context, digest.data(), &length) == 1;
  EVP_MD_CTX_free(context);
  if (!ok) throw DatasetError("OpenSSL could not compute the SHA-256 job id");
  std::string hex(2 * length, '0');
  for (unsigned int i = 0; i < length; ++i) {
    std::snprintf(hex.data() + 2 * i, 3, "%02x", digest[i]);
  }
  return hex;
}

}  // namespace grip::io
