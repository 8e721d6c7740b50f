// SPDX-License-Identifier: GPL-3.0-or-later
#include "hid_text.h"

#include <hidapi/hidapi.h>

#include <mutex>

#include "hapticad/devices/device.h"

namespace hapticad::hid {

std::mutex& GlobalStateMutex() {
  static std::mutex mutex;
  return mutex;
}

void EnsureHidInit() {
  static std::once_flag once;
  static int result = 0;
  static std::string why;  // hidapi's words at the failure, before another call replaces them
  std::call_once(once, [] {
    std::lock_guard<std::mutex> lock(GlobalStateMutex());
    result = hid_init();
    if (result != 0) why = ErrorText(nullptr);
  });
  if (result != 0) throw DeviceError("cannot initialise hidapi: " + why);
}

std::string ToUtf8(const wchar_t* text) {
  std::string out;
  if (!text) return out;
  for (; *text; ++text) {
    const auto c = static_cast<char32_t>(*text);
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x110000) {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

std::string ErrorText(hid_device* handle) {
  const std::string text = ToUtf8(hid_error(handle));
  return text.empty() ? "unknown error" : text;
}

std::string ProductName(hid_device* handle) {
  wchar_t name[256] = {};
  if (hid_get_product_string(handle, name, 255) == 0 && name[0] != 0) return ToUtf8(name);
  return "HaptiCAD protocol device";
}

}  // namespace hapticad::hid
