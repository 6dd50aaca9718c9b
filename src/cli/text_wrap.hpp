#pragma once
// Text for the terminal, wrapped at word boundaries.
#include <cstddef>
#include <string>

namespace granchain {

// `text` in lines of at most `width` characters of words (a longer word stands alone), the first
// line after `first`, each further one after `indent`; lines joined by '\n', none at the end.
std::string wrap_words(const std::string& text, std::size_t width, const std::string& first = "", const std::string& indent = "");

}  // namespace granchain
