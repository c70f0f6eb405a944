// libFuzzer target for the scene parser. Properties checked on every input:
//  - it either parses or throws SceneError: no other exception, no crash, no sanitizer report;
//  - a scene that parses resolves to text that parses back to the same resolved text.
// Input: scene text; bytes after a 0x01 byte are --set overrides, one per line.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mpmshock/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\x01');
  const std::string text = input.substr(0, split);
  std::vector<std::string> overrides;
  if (split != std::string::npos) {
    std::size_t start = split + 1;
    while (start <= input.size()) {
      const std::size_t end = input.find('\n', start);
      overrides.push_back(input.substr(start, end == std::string::npos ? std::string::npos : end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  std::string resolved;
  try {
    resolved = mpmshock::resolved_scene(mpmshock::parse_scene(text, "fuzz", overrides));
  } catch (const mpmshock::SceneError&) {
    return 0;
  }
  try {
    const std::string again = mpmshock::resolved_scene(mpmshock::parse_scene(resolved, "resolved"));
    if (again != resolved) {
      std::fprintf(stderr, "resolved scene does not read back to itself:\n%s\n---\n%s\n", resolved.c_str(), again.c_str());
      std::abort();
    }
  } catch (const mpmshock::SceneError& e) {
    std::fprintf(stderr, "resolved scene does not parse: %s\n%s\n", e.what(), resolved.c_str());
    std::abort();
  }
  return 0;
}
