#include "ObjTokens.h"

#include <charconv>
#include <sstream>

namespace sylva::plantimport {

std::vector<std::string> statementWords(const std::string& line) {
    std::vector<std::string> words;
    std::istringstream stream(line.substr(0, line.find('#')));
    std::string word;
    while (stream >> word) {
        words.push_back(word);
    }
    return words;
}

Status forEachStatement(
    const std::string& text,
    const std::function<Status(const std::vector<std::string>& words, int line)>& statement) {
    std::istringstream lines(text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        const std::vector<std::string> words = statementWords(line);
        if (words.empty()) {
            continue;
        }
        if (Status read = statement(words, number); !read) {
            return read;
        }
    }
    return Status::success();
}

bool parseFloat(const std::string& text, float& value) {
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

std::string mapFileName(const std::vector<std::string>& words) {
    std::size_t i = 1;
    while (i + 1 < words.size() && words[i].size() > 1 && words[i][0] == '-') {
        i += words[i] == "-o" || words[i] == "-s" || words[i] == "-t" ? 4 : 2;
    }
    std::string name;
    for (; i < words.size(); ++i) {
        name += (name.empty() ? "" : " ") + words[i];
    }
    return name;
}

}  // namespace sylva::plantimport
