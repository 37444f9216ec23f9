#pragma once
/// @file
/// A command line shown to a person exactly: each word quoted as a POSIX
/// shell reads it back. A command read from a log is hostile input, so the
/// text shown must neither hide a word (spaces, quotes) nor let a byte of it
/// act on the terminal (an escape sequence): a word with a control byte or a
/// byte outside ASCII is written in bash's $'...' form, those bytes as \xHH.

#include <string>
#include <vector>

namespace lagrange::tools {

/// One word, quoted: 'a b' -> "'a b'", it's -> "'it'\''s'", "\x1b[2J" -> "$'\x1b[2J'".
std::string shellWord(const std::string& word);

/// The words quoted and joined by spaces; at most `limit` characters, the
/// rest replaced by "... (N more characters)".
std::string shellWords(const std::vector<std::string>& words, std::size_t limit = 2000);

}  // namespace lagrange::tools
