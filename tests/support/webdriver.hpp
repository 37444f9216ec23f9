#pragma once
/// @file
/// Debian's chromium, headless, driven over the W3C WebDriver protocol by
/// Debian's chromedriver, from GoogleTest: open a page, run a script in it,
/// read its console, take a screenshot. The HTTP client is cpp-httplib, the
/// library `lagrange view` serves with. Chromium's flags are those that keep
/// it off the network (no background requests, no component updates, no QUIC)
/// and let it run as root without a GPU (software WebGL).

#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/child.hpp"

namespace lagrange::testing {

/// A free TCP port on loopback (the kernel's pick, released for the caller).
inline int freeLoopbackPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr);
  socklen_t len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  close(fd);
  return ntohs(addr.sin_port);
}

inline std::string base64Decode(const std::string& in) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string out;
  int bits = 0;
  uint32_t buffer = 0;  // the bits not yet written: fewer than 8 before each shift
  for (char c : in) {
    const int v = value(c);
    if (v < 0) continue;  // padding, line breaks
    buffer = ((buffer & 0xff) << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((buffer >> bits) & 0xff));
    }
  }
  return out;
}

class Browser {
 public:
  /// Starts chromedriver and a headless chromium with a window of width x height.
  Browser(const std::string& work_dir, int width, int height)
      : port_(freeLoopbackPort()),
        // Without DISPLAY: headless chromium given an X display it cannot
        // reach (a test before this one set it) fails to create WebGL contexts.
        driver_({"env", "-u", "DISPLAY", "chromedriver", "--port=" + std::to_string(port_)},
                work_dir + "/chromedriver.log"),
        http_("127.0.0.1", port_) {
    http_.set_read_timeout(60, 0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (true) {
      const auto res = http_.Get("/status");
      if (res && res->status == 200 && nlohmann::json::parse(res->body)["value"].value("ready", false)) break;
      if (std::chrono::steady_clock::now() > deadline)
        throw std::runtime_error("chromedriver did not start (see " + work_dir + "/chromedriver.log)");
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    const nlohmann::json args = {"--headless",
                                 "--no-sandbox",
                                 "--disable-gpu",
                                 "--enable-unsafe-swiftshader",
                                 "--disable-quic",
                                 "--no-first-run",
                                 "--disable-background-networking",
                                 "--disable-component-update",
                                 "--disable-sync",
                                 "--force-device-scale-factor=1",
                                 "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                 "--user-data-dir=" + work_dir + "/chromium-profile"};
    const nlohmann::json caps = {
        {"capabilities",
         {{"alwaysMatch",
           {{"browserName", "chrome"},
            {"goog:loggingPrefs", {{"browser", "ALL"}}},
            {"goog:chromeOptions", {{"binary", "/usr/bin/chromium"}, {"args", args}}}}}}}};
    session_ = call("POST", "/session", caps)["sessionId"].get<std::string>();
  }
  ~Browser() {
    if (!session_.empty()) http_.Delete(("/session/" + session_).c_str());
    driver_.signal(SIGTERM);
    driver_.wait(10);
  }
  Browser(const Browser&) = delete;
  Browser& operator=(const Browser&) = delete;

  void open(const std::string& url) { call("POST", path("/url"), {{"url", url}}); }

  /// Runs `script` (a function body: `return ...;`) in the page; its value.
  nlohmann::json run(const std::string& script, const nlohmann::json& args = nlohmann::json::array()) {
    return call("POST", path("/execute/sync"), {{"script", script}, {"args", args}});
  }

  /// Polls `expression` until it is true; false after `seconds`.
  bool waitUntil(const std::string& expression, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < deadline) {
      if (run("return !!(" + expression + ");").get<bool>()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }

  /// The page's console and network messages so far ({level, message, source}).
  std::vector<nlohmann::json> consoleLog() {
    const nlohmann::json entries = call("POST", path("/se/log"), {{"type", "browser"}});
    return {entries.begin(), entries.end()};
  }

  /// The viewport as PNG bytes.
  std::string screenshotPng() { return base64Decode(call("GET", path("/screenshot")).get<std::string>()); }

 private:
  std::string path(const std::string& tail) const { return "/session/" + session_ + tail; }
  nlohmann::json call(const std::string& method, const std::string& where, const nlohmann::json& body = {}) {
    const auto res = method == "GET" ? http_.Get(where.c_str())
                                     : http_.Post(where.c_str(), body.dump(), "application/json");
    if (!res) throw std::runtime_error("chromedriver did not answer " + method + " " + where);
    const nlohmann::json reply = nlohmann::json::parse(res->body);
    if (res->status != 200)
      throw std::runtime_error("chromedriver: " + method + " " + where + ": " + reply.dump().substr(0, 600));
    return reply["value"];
  }

  int port_;
  Child driver_;
  httplib::Client http_;
  std::string session_;
};

}  // namespace lagrange::testing
