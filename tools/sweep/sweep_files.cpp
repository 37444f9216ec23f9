#include "tools/sweep/sweep_files.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "util/input_file.hpp"

namespace lagrange::tools {

namespace {

// Thrown out of nlohmann's parser by the callback, at the first level too deep.
struct TooDeep {};

}  // namespace

std::optional<nlohmann::ordered_json> parseSweepJson(const std::string& text, std::string& error) {
  // The parser calls back at each value's start with its depth, before it
  // builds anything below: the parse stops there.
  const nlohmann::ordered_json::parser_callback_t depth_check =
      [](int depth, nlohmann::ordered_json::parse_event_t event, nlohmann::ordered_json&) {
        if ((event == nlohmann::ordered_json::parse_event_t::object_start ||
             event == nlohmann::ordered_json::parse_event_t::array_start) &&
            depth >= kMaxSweepJsonDepth)
          throw TooDeep{};
        return true;
      };
  try {
    return nlohmann::ordered_json::parse(text, depth_check);
  } catch (const TooDeep&) {
    error = "nested deeper than " + std::to_string(kMaxSweepJsonDepth) + " levels";
  } catch (const nlohmann::ordered_json::exception& e) {
    error = std::string("not JSON (") + e.what() + ")";
  }
  return std::nullopt;
}

std::optional<std::string> readSweepFile(const std::string& path, const std::string& expected,
                                         long long max_bytes, std::string& error) {
  const util::InputFile file = util::InputFile::open(path, expected, util::Links::kRefuse);
  if (!file.ok()) {
    error = file.error();
    return std::nullopt;
  }
  if (file.size() > max_bytes) {
    error = "'" + path + "' holds " + std::to_string(file.size()) + " bytes; expected " + expected +
            " of at most " + std::to_string(max_bytes) + " bytes";
    return std::nullopt;
  }
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t got = read(file.fd(), buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      error = "cannot read '" + path + "' (" + std::strerror(errno) + "); expected " + expected;
      return std::nullopt;
    }
    if (got == 0) return text;
    text.append(buf, static_cast<std::size_t>(got));
    if (static_cast<long long>(text.size()) > max_bytes) {  // grown since it was opened: read no further
      error = "'" + path + "' grew past " + std::to_string(max_bytes) +
              " bytes while it was read; expected " + expected + " of at most that";
      return std::nullopt;
    }
  }
}

std::string forEachLine(const std::string& path, const std::string& expected, long long max_file_bytes,
                        const std::function<bool(const FileLine&)>& on_line, std::optional<uid_t> owner) {
  const util::InputFile file = util::InputFile::open(path, expected, util::Links::kRefuse);
  if (!file.ok()) return file.error();
  if (owner && file.owner() != *owner)
    return "'" + path + "' belongs to user " + std::to_string(file.owner()) + "; expected " + expected +
           ", which belongs to user " + std::to_string(*owner) + " as the sweep's plan.json does";
  if (file.size() > max_file_bytes)
    return "'" + path + "' holds " + std::to_string(file.size()) + " bytes; expected " + expected +
           " of at most " + std::to_string(max_file_bytes) + " bytes";
  FileLine line;
  line.number = 1;
  char buf[65536];
  long long total = 0;
  for (;;) {
    const ssize_t got = read(file.fd(), buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) return "cannot read '" + path + "' (" + std::strerror(errno) + "); expected " + expected;
    if (got == 0) return "";  // what is left in `line` has no newline: a writer killed mid-line
    total += got;
    if (total > max_file_bytes)  // grown since it was opened: read no further
      return "'" + path + "' grew past " + std::to_string(max_file_bytes) +
             " bytes while it was read; expected " + expected + " of at most that";
    for (ssize_t i = 0; i < got; ++i) {
      if (buf[i] != '\n') {
        if (line.text.size() < kMaxSweepLineBytes)
          line.text.push_back(buf[i]);
        else
          line.too_long = true;
        continue;
      }
      if (!on_line(line)) return "";
      line.text.clear();
      line.too_long = false;
      ++line.number;
    }
  }
}

}  // namespace lagrange::tools
