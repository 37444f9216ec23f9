#include "tools/view/view.hpp"

#include <arpa/inet.h>
#include <httplib.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include "config/input_file.hpp"
#include "runtime/key_file.hpp"
#include "tools/command_error.hpp"
#include "tools/spy/spy.hpp"
#include "tools/view/view_host_check.hpp"
#include "tools/view/view_server.hpp"
#include "tools/view/view_source.hpp"
#include "util/error.hpp"
#include "util/terminal_text.hpp"
#include "wiring/netns.hpp"

namespace lagrange::tools {

namespace fs = std::filesystem;

namespace {

volatile std::sig_atomic_t view_signal = 0;
void onViewSignal(int signal) { view_signal = signal; }

constexpr const char* kThreeDir = "/usr/share/javascript/three";
// The most frames a log sends to the page, and a live update at most: the
// page plots and draws them, more would only slow it.
constexpr size_t kMaxLogFrames = 20000;
constexpr size_t kMaxLiveBatch = 200;

struct Source {
  bool live = false;
  std::string what;  ///< for the start line
  std::string log_path;
  std::string lcm_url;
  int64_t run_id = 0;
  std::optional<long> netns_pid;
  std::string key_file;  ///< live: the run's key, to read only what its processes sent
};

// A directory with a going run is live; a finished one is its log.
Source resolveSource(const ViewOptions& opt) {
  Source s;
  if (opt.source.empty()) {
    if (opt.lcm_url.empty())
      throw BadInput("nothing to view: expected a run's output directory, a log file, or --lcm-url URL");
    s.live = true;
    s.lcm_url = opt.lcm_url;
    s.key_file = opt.key_file;
    s.what = "live traffic on " + opt.lcm_url;
    return s;
  }
  if (!fs::exists(opt.source))
    throw BadInput(opt.source + " does not exist; expected a run's output directory or a log file");
  if (fs::is_directory(opt.source)) {
    if (fs::exists(fs::path(opt.source) / "lcm.json")) {
      const RunEndpoint e = readEndpoint(opt.source);
      if (e.launcher_pid && launcherAlive(*e.launcher_pid)) {
        s.live = true;
        s.lcm_url = opt.lcm_url.empty() ? e.lcm_url : opt.lcm_url;
        s.run_id = e.run_id;
        s.netns_pid = e.netns_pid;
        s.key_file = opt.key_file.empty() ? (fs::path(opt.source) / "run.key").string() : opt.key_file;
        s.what = "the running scenario in " + opt.source;
        return s;
      }
    }
    s.log_path = (fs::path(opt.source) / "run.lcm").string();
    if (!fs::exists(s.log_path))
      throw BadInput(opt.source +
                     " holds no run.lcm and no running scenario; expected the output directory of "
                     "`lagrange run`");
  } else {
    s.log_path = opt.source;
  }
  s.what = s.log_path;
  return s;
}

std::string readFile(const fs::path& path, const std::string& what_provides_it) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path.string() + " not found; " + what_provides_it);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The page's own files (tools/view/web, copied next to the programs) and three.js.
struct Assets {
  std::vector<std::pair<std::string, std::pair<std::string, std::string>>> files;  // path -> (type, body)
};

Assets loadAssets() {
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  const fs::path web = exe_dir.parent_path() / "share/lagrange/web";
  const std::string build_hint = "build the project (bash scripts/build.sh) or reinstall it";
  const std::string three_hint = "install Debian's libjs-three";
  Assets a;
  a.files = {
      {"/", {"text/html; charset=utf-8", readFile(web / "index.html", build_hint)}},
      {"/viewer.js", {"text/javascript; charset=utf-8", readFile(web / "viewer.js", build_hint)}},
      {"/plots.js", {"text/javascript; charset=utf-8", readFile(web / "plots.js", build_hint)}},
      {"/viewer.css", {"text/css; charset=utf-8", readFile(web / "viewer.css", build_hint)}},
      {"/three/three.min.js",
       {"text/javascript; charset=utf-8", readFile(fs::path(kThreeDir) / "build/three.min.js", three_hint)}},
      {"/three/OrbitControls.js",
       {"text/javascript; charset=utf-8",
        readFile(fs::path(kThreeDir) / "examples/js/controls/OrbitControls.js", three_hint)}},
  };
  return a;
}

std::vector<std::string> warnings(const ViewLog& log) {
  std::vector<std::string> all = log.scan.problems();
  all.insert(all.end(), log.notes.begin(), log.notes.end());
  return all;
}

// The verdict of the run whose log this is (summary.json beside a run.lcm),
// as the run wrote it: shown, never decided here. Null when there is none,
// or when the file is not a regular one of a summary's size (a warning says so).
nlohmann::json runVerdictBeside(const std::string& log_path, std::vector<std::string>& notes) {
  const fs::path log(log_path);
  const fs::path summary = log.parent_path() / "summary.json";
  std::error_code ec;
  if (log.filename() != "run.lcm" || !fs::exists(fs::symlink_status(summary, ec))) return nullptr;
  const config::FileText file =
      config::readRegularFile(summary.string(), 16u << 20, "the run's summary.json");
  if (!file.error.empty()) {
    notes.push_back(file.error + "; the run's verdict is not shown");
    return nullptr;
  }
  try {
    const nlohmann::json j = nlohmann::json::parse(file.text);
    if (j.is_object() && j.contains("verdict") && j["verdict"].is_object() &&
        j["verdict"].value("headline", nlohmann::json()).is_string())
      return {{"headline", j["verdict"]["headline"]}, {"met", j["verdict"].value("met", false)}};
  } catch (const nlohmann::json::parse_error&) {
    notes.push_back(summary.string() + " is not JSON; the run's verdict is not shown");
  } catch (const nlohmann::json::exception&) {
    notes.push_back(summary.string() + " has no verdict of the expected shape; it is not shown");
  }
  return nullptr;
}

std::string logJson(const ViewLog& log, const nlohmann::json& verdict) {
  // Every k-th frame and the last one, at most kMaxLogFrames.
  const size_t n = log.frames.size();
  const size_t stride = std::max<size_t>(1, (n + kMaxLogFrames - 1) / kMaxLogFrames);
  std::vector<size_t> sent;
  for (size_t i = 0; i < n; i += stride) sent.push_back(i);
  if (n > 0 && (n - 1) % stride != 0) sent.push_back(n - 1);
  std::vector<ViewFrame> frames;
  for (const size_t i : sent) frames.push_back(log.frames[i]);
  nlohmann::json j = {{"description", descriptionJson(log.description)},
                      {"frames", framesJson(frames)},
                      {"stride", stride},
                      {"warnings", warnings(log)},
                      {"verdict", verdict}};
  // The plots' peaks between the frames sent (view_frames.hpp).
  if (stride > 1) j["envelope"] = envelopeJson(log.frames, sent);
  return j.dump();
}

void serveLive(GuardedHttpServer& server, LiveFeed& feed) {
  server.Get("/api/live", [&feed, &server](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    // Each open stream holds a connection for as long as its page is open:
    // bounded, so that pages can still be loaded beside them.
    std::shared_ptr<void> slot = server.tryOpenStream();
    if (!slot) {
      res.status = 503;
      res.set_content("the viewer has " + std::to_string(server.limits().max_live_streams) +
                          " live streams open, its limit; close a viewer tab\n",
                      "text/plain");
      return;
    }
    auto next = std::make_shared<uint64_t>(0);
    auto described = std::make_shared<bool>(false);
    res.set_chunked_content_provider(
        "text/event-stream", [&feed, next, described, slot](size_t, httplib::DataSink& sink) {
          if (view_signal != 0) return false;
          const LiveFeed::Update u = feed.waitFrom(*next, kMaxLiveBatch, std::chrono::milliseconds(100));
          std::string out;
          if (u.description && !*described) {
            out += "event: description\ndata: " + descriptionJson(*u.description).dump() + "\n\n";
            *described = true;
          }
          if (!u.frames.empty()) out += "event: frames\ndata: " + framesJson(u.frames).dump() + "\n\n";
          if (out.empty()) out = ": waiting\n\n";  // a comment: keeps the connection and notices a closed one
          *next = u.next;
          return sink.write(out.data(), out.size());
        });
  });
}

}  // namespace

bool isLoopbackHost(const std::string& host) {
  if (host == "localhost") return true;
  in_addr v4{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  return inet_pton(AF_INET6, host.c_str(), &v6) == 1 && IN6_IS_ADDR_LOOPBACK(&v6);
}

int runView(const ViewOptions& opt) {
  std::unique_ptr<ViewLog> log;
  Source source;
  Assets assets;
  GuardedHttpServer server;
  int port = opt.port;
  try {
    if (!isLoopbackHost(opt.host) && !opt.allow_remote)
      throw BadInput(
          "--host " + opt.host +
          " is not a loopback address: the viewer has no authentication and anyone who reaches it "
          "sees the run; expected 127.0.0.1, ::1 or localhost, or --allow-remote to serve it anyway");
    if (opt.port < 0 || opt.port > 65535)
      throw BadInput("--port " + std::to_string(opt.port) +
                     " is not a port; expected 0 (any free port) to 65535");
    source = resolveSource(opt);
    assets = loadAssets();
    if (!source.live) log = std::make_unique<ViewLog>(readViewLog(source.log_path));
    // Bound here, before a run's namespace is joined: the page is reached
    // from this machine's network, the run's traffic from its own.
    port = server.bindPort(opt.host, opt.port);
    if (port < 0)
      throw BadInput(
          "cannot listen on " + opt.host + ":" + std::to_string(opt.port) +
          " (in use, or not an address of this machine); expected a free port (--port 0 picks one)");
    if (source.netns_pid) wiring::joinNetnsOf(*source.netns_pid);
  } catch (const std::exception& e) {
    return failWith("lagrange view", e);
  }

  std::unique_ptr<LiveFeed> feed;
  try {
    if (source.live) {
      std::optional<transport::MessageKey> key;
      if (!source.key_file.empty()) {
        try {
          key = runtime::readKeyFile(source.key_file);
        } catch (const std::exception& e) {  // a ConfigError, bad input (config/ is not included
                                             // here: its Eigen breaks after httplib's resolv.h)
          return failWith("lagrange view", e);
        }
      } else {
        std::cerr << "lagrange view: warning: no --key-file: the page draws whatever reaches "
                  << source.lcm_url << " unauthenticated (anyone on the group can draw into it)\n";
      }
      feed = std::make_unique<LiveFeed>(source.lcm_url, source.run_id, key);
    }
  } catch (const std::exception& e) {
    return failWith("lagrange view", e);
  }

  // DNS rebinding: a page of another site, its name resolved to this
  // address, would otherwise read the run through the visitor's browser.
  server.set_pre_routing_handler(
      [policy = hostPolicy(opt.host, opt.allow_remote)](const httplib::Request& req, httplib::Response& res) {
        // Every Host header, each value whole (get_header_value gives the
        // first, cut at a NUL): view_host_check.hpp.
        std::vector<std::string> hosts;
        for (auto [at, end] = req.headers.equal_range("Host"); at != end; ++at) hosts.push_back(at->second);
        const std::string why = hostRefusal(hosts, policy);
        if (why.empty()) return httplib::Server::HandlerResponse::Unhandled;
        res.status = 421;  // Misdirected Request: not a name this server answers to
        res.set_content("lagrange view: " + why + "\n", "text/plain");
        return httplib::Server::HandlerResponse::Handled;
      });
  for (const auto& [path, file] : assets.files) {
    const auto& [type, body] = file;
    server.Get(path, [type = type, body = body](const httplib::Request&, httplib::Response& res) {
      res.set_content(body, type.c_str());
    });
  }
  const nlohmann::json session = {{"mode", source.live ? "live" : "log"}, {"source", source.what}};
  server.Get("/api/session", [session](const httplib::Request&, httplib::Response& res) {
    res.set_content(session.dump(), "application/json");
  });
  if (log) {
    std::vector<std::string> notes;
    const nlohmann::json verdict = runVerdictBeside(source.log_path, notes);
    for (const std::string& n : notes) std::cerr << "lagrange view: " << util::terminalSafeLines(n) << "\n";
    const std::string body = logJson(*log, verdict);
    server.Get("/api/log", [body](const httplib::Request&, httplib::Response& res) {
      res.set_content(body, "application/json");
    });
    for (const std::string& w : warnings(*log))
      std::cerr << "lagrange view: " << util::terminalSafeLines(w) << "\n";
  }
  if (feed) serveLive(server, *feed);

  std::signal(SIGINT, onViewSignal);
  std::signal(SIGTERM, onViewSignal);
  std::signal(SIGPIPE, SIG_IGN);
  std::atomic<bool> served{false};
  std::thread stopper([&server, &served] {
    while (view_signal == 0 && !served) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.stop();
  });
  const std::string shown_host = opt.host.find(':') != std::string::npos ? "[" + opt.host + "]" : opt.host;
  std::cout << "lagrange view: " << source.what << " at http://" << shown_host << ":" << port
            << "/ (Ctrl-C stops)" << std::endl;
  const bool listened = server.listen_after_bind();
  const bool stopped = view_signal != 0;
  served = true;  // also when the server ended on its own
  stopper.join();
  // Why a live page stayed empty, if it did: nothing came, or what came was not this run's.
  if (feed)
    std::cerr << "lagrange view: " << feed->received() << " messages drawn from, " << feed->rejected()
              << " rejected (undecodable, corrupted, or of another run)\n";
  if (server.refusedConnections() > 0)
    std::cerr << "lagrange view: " << server.refusedConnections() << " connections refused (more than "
              << server.limits().max_connections << " open at once)\n";
  if (!listened && !stopped) {
    std::cerr << "lagrange view: the server stopped accepting connections on " << shown_host << ":" << port
              << "\n";
    return kExitFailed;
  }
  return kExitOk;
}

}  // namespace lagrange::tools
