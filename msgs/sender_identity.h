#pragma once
// Helpers for the sender identity of probe_pose_t (version 2), shared by the
// server and the clients so that both read and print session ids the same
// way. Header-only, no dependencies beyond the standard library.
//   sender_session: random non-zero 64-bit id drawn by the client at start;
//   sender_device:  device name, at most kMaxDeviceNameBytes.
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <string_view>

namespace haptics_msgs {

inline constexpr size_t kMaxDeviceNameBytes = 64;

// "0x" and 16 hex digits (the id as unsigned): how clients print their
// session and the server logs and reports it.
inline std::string FormatSession(int64_t session) {
  char text[24];
  std::snprintf(text, sizeof(text), "0x%016" PRIx64, static_cast<uint64_t>(session));
  return text;
}

// Reads a session id written as 0x-prefixed hex or as decimal (unsigned
// 64-bit). False if it is not such a number, does not fit, or is 0.
inline bool ParseSession(std::string_view text, int64_t* session) {
  const std::string s(text);
  if (s.empty() || !(s[0] >= '0' && s[0] <= '9')) return false;
  const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
  if (hex && !std::isxdigit(static_cast<unsigned char>(s[2]))) return false;
  errno = 0;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(s.c_str(), &end, hex ? 16 : 10);
  if (errno != 0 || end == s.c_str() || *end != '\0' || v == 0) return false;
  *session = static_cast<int64_t>(static_cast<uint64_t>(v));
  return true;
}

// A fresh random non-zero session id (std::random_device: the kernel's
// entropy, so two clients started at the same instant still differ).
inline int64_t NewSession() {
  std::random_device rd;
  uint64_t v = 0;
  while (v == 0) v = (static_cast<uint64_t>(rd()) << 32) ^ static_cast<uint64_t>(rd());
  return static_cast<int64_t>(v);
}

}  // namespace haptics_msgs
