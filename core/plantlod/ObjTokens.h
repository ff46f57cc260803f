// ObjTokens: the lexical rules Wavefront OBJ and its MTL files share: statements are
// white-space separated words up to a `#`, numbers are plain decimal floats, and a
// map statement's file name is the rest of the line after its options.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"

namespace sylva::plantimport {

// The words of a line without its comment.
std::vector<std::string> statementWords(const std::string& line);

// Calls `statement(words, line number)` for every line of `text` that has words, in
// order; stops at the first failure and returns it.
Status forEachStatement(
    const std::string& text,
    const std::function<Status(const std::vector<std::string>& words, int line)>& statement);

// The whole text as a float (from_chars); false for anything else.
bool parseFloat(const std::string& text, float& value);

// The rest of a line after its keyword (file names may contain spaces); options such as
// "-bm 1" before the file name are skipped (-o, -s and -t take three values).
std::string mapFileName(const std::vector<std::string>& words);

}  // namespace sylva::plantimport
