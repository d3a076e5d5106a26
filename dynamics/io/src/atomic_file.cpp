#include "rockcontact/dynamics/io/atomic_file.hpp"

#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

namespace rockcontact::dynamics {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path target)
    : target_(std::move(target)), partial_(target_.string() + ".partial") {
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    pending_ = false;
    throw OutputError("cannot write " + target_.string() + ": " + std::strerror(errno));
  }
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : target_(std::move(other.target_)),
      partial_(std::move(other.partial_)),
      out_(std::move(other.out_)),
      pending_(std::exchange(other.pending_, false)) {}

AtomicFile::~AtomicFile() { discard(); }

void AtomicFile::discard() noexcept {
  if (!pending_) return;
  pending_ = false;
  out_.close();
  std::error_code ignored;  // nothing better to do about a leftover in a destructor
  fs::remove(partial_, ignored);
}

void AtomicFile::commit() {
  out_.close();
  if (!out_) {
    discard();
    throw OutputError("cannot write " + target_.string() + ": write failed");
  }
  std::error_code error;
  fs::rename(partial_, target_, error);
  if (error) {
    discard();
    throw OutputError("cannot write " + target_.string() + ": " + error.message());
  }
  pending_ = false;
}

}  // namespace rockcontact::dynamics
