#include "cli/text_wrap.hpp"

namespace granchain {

std::string wrap_words(const std::string& text, std::size_t width, const std::string& first, const std::string& indent) {
  std::string out = first, line;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n" + indent;
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  return out + line;
}

}  // namespace granchain
