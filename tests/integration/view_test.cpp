// `lagrange view` in a real browser: Debian's chromium, headless, driven
// over WebDriver (tests/support/webdriver.hpp). The page must load without a
// console error; at a log time the tip must be drawn where the arm's own
// forward kinematics puts it at the logged angles (found in a screenshot by
// its colour, against the page's camera); seek, speed and pause must move the
// page's clock as asked; a running scenario must be followed live. Planar
// chain, URDF arm and flexible joints each draw from their logs.
//
// LAGRANGE_VIEW_SCREENSHOT=PATH keeps a screenshot of the flexible arm's log.
// The README's docs/view.png is taken as docs/viewer.md says, with
// tools/view/screenshot.py, which waits for the page's ready signal: tested here too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <regex>
#include <sstream>

#include "config/scenario.hpp"
#include "logs/log_reader.hpp"
#include "support/child.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/png_image.hpp"
#include "support/run_log.hpp"
#include "support/wait.hpp"
#include "support/webdriver.hpp"
#include "transport/channels.hpp"

namespace lagrange::testing {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kTipRgb[3] = {255, 0, 255};    // viewer.js TIP_COLOR
constexpr int kRotorRgb[3] = {240, 140, 0};  // viewer.js ROTOR_COLOR

// `lagrange view SOURCE --port 0` in the background, and the URL it printed.
class ViewServer {
 public:
  ViewServer(const std::string& source, const std::string& dir)
      : output_(dir + "/view.out"), child_({kBin + "/lagrange", "view", source, "--port", "0"}, output_) {
    const std::regex url(R"((http://127\.0\.0\.1:[0-9]+/))");
    waitFor(
        [&] {
          std::smatch m;
          const std::string text = slurp(output_);
          if (!std::regex_search(text, m, url)) return !child_.running();
          url_ = m[1];
          return true;
        },
        30);
  }
  ~ViewServer() { child_.signal(SIGTERM); }
  const std::string& url() const { return url_; }
  std::string output() const { return slurp(output_); }
  /// SIGTERM, then its exit code.
  int stop() {
    child_.signal(SIGTERM);
    return child_.wait(10);
  }

 private:
  std::string output_;
  Child child_;
  std::string url_;
};

struct Logged {
  std::map<double, std::vector<double>> q, motor;  // by sim_time
};

Logged readLogged(const std::string& log) {
  Logged out;
  logs::readLog(log, [&](const lcm::LogEvent& ev) {
    if (ev.channel == transport::kPlantTruth) {
      lagrange::plant_truth_t m;
      if (logs::decodeEvent(ev, m)) out.q.emplace(m.header.sim_time, m.q);
    } else if (ev.channel == transport::kPlantMotor) {
      lagrange::plant_motor_t m;
      if (logs::decodeEvent(ev, m)) out.motor.emplace(m.header.sim_time, m.q);
    }
  });
  return out;
}

Eigen::VectorXd vec(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), v.size());
}

std::string inprocLog(const std::string& config, const std::string& dir, const std::string& sets) {
  const RunResult r = runScenario(kConfigs + "/" + config, dir + "/run", "--mode inproc -q " + sets);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return dir + "/run/run.lcm";
}

// Opens the page and waits for its ready signal (viewer.js): <body
// data-ready="true"> once its first frame is on the screen, as a headless
// screenshot waits for it (docs/viewer.md).
void openViewer(Browser& browser, const ViewServer& server) {
  ASSERT_FALSE(server.url().empty()) << server.output();
  browser.open(server.url());
  ASSERT_TRUE(browser.waitUntil("document.body.dataset.ready", 30))
      << browser.run("return document.getElementById('status').textContent;").dump();
  ASSERT_EQ(browser.run("return document.body.dataset.ready;"), "true")
      << browser.run("return document.getElementById('status').textContent;").dump();
  EXPECT_TRUE(browser.run("return window.lagrangeViewer.ready;").get<bool>());  // loaded before drawn
}

void expectNoConsoleError(Browser& browser) {
  for (const json& entry : browser.consoleLog())
    EXPECT_NE(entry.value("level", ""), "SEVERE") << entry.dump();
  EXPECT_EQ(browser.run("return document.getElementById('status').textContent;").get<std::string>(), "");
}

json seekTo(Browser& browser, double t) {
  return browser.run(
      "const s = document.getElementById('seek'); s.value = arguments[0];"
      "s.dispatchEvent(new Event('input')); return window.lagrangeViewer.state();",
      {t});
}

struct TipCheck {
  double expected_x, expected_y;
  ColourBlob drawn;
  long rotor_pixels;
};

// Seeks to logged time t, then finds the tip's colour in a screenshot and
// where the arm's own forward kinematics at the logged q puts it.
TipCheck drawnTip(Browser& browser, const model::RobotModel& arm, const Logged& logged, double t,
                  const std::string& keep_png = "") {
  const json state = seekTo(browser, t);
  EXPECT_NEAR(state["t"].get<double>(), t, 1e-12);
  EXPECT_EQ(state["frameT"].get<double>(), t);
  const std::vector<double> q = logged.q.at(t);
  EXPECT_EQ(state["q"].get<std::vector<double>>(), q)
      << "the page draws another frame than the log's at t = " << t;
  if (!logged.motor.empty()) {
    EXPECT_EQ(state["motor"].get<std::vector<double>>(), logged.motor.at(t));
  }
  // Until the frame sought is on the screen (drawn, then an animation frame).
  EXPECT_TRUE(
      browser.waitUntil("window.lagrangeViewer.state().presentedT === window.lagrangeViewer.state().t", 5))
      << browser.run("return window.lagrangeViewer.state();").dump();
  const Eigen::Vector3d tip = arm.tipPosition(vec(q));
  const json expected =
      browser.run("return window.lagrangeViewer.project(arguments[0]);", {{tip.x(), tip.y(), tip.z()}});
  const json box = browser.run(
      "const r = document.querySelector('#scene canvas').getBoundingClientRect();"
      "return [r.left, r.top, r.right, r.bottom];");
  const std::string png = browser.screenshotPng();
  if (!keep_png.empty()) std::ofstream(keep_png, std::ios::binary) << png;
  const RgbaImage image = decodePng(png);
  const int x0 = box[0].get<int>(), y0 = box[1].get<int>(), x1 = box[2].get<int>(), y1 = box[3].get<int>();
  TipCheck c;
  c.expected_x = expected[0].get<double>();
  c.expected_y = expected[1].get<double>();
  c.drawn = findColour(image, kTipRgb[0], kTipRgb[1], kTipRgb[2], 40, x0, y0, x1, y1);
  c.rotor_pixels = findColour(image, kRotorRgb[0], kRotorRgb[1], kRotorRgb[2], 40, x0, y0, x1, y1).count;
  EXPECT_GT(c.drawn.count, 20) << "no tip drawn at t = " << t;
  EXPECT_NEAR(c.drawn.x, c.expected_x, 2.0) << "t = " << t;
  EXPECT_NEAR(c.drawn.y, c.expected_y, 2.0) << "t = " << t;
  return c;
}

// The logged time nearest t.
double loggedTimeNear(const Logged& logged, double t) {
  auto it = logged.q.lower_bound(t);
  if (it == logged.q.end()) --it;
  return it->first;
}

TEST(View, APlanarLogIsDrawnWhereItsAnglesPutTheTip) {
  const std::string dir = freshDir("view-planar");
  fs::create_directories(dir);
  const std::string log = inprocLog("rigid_2dof.yaml", dir, "--set duration=1");
  const Logged logged = readLogged(log);
  const config::Scenario s = config::loadScenario(kConfigs + "/rigid_2dof.yaml");
  ViewServer server(log, dir);
  Browser browser(dir, 1280, 720);
  openViewer(browser, server);
  EXPECT_EQ(browser.run("return window.lagrangeViewer.state().mode;"), "log");
  // The run's verdict, as its summary.json beside run.lcm has it.
  EXPECT_EQ(
      browser.run("const v = document.getElementById('verdict'); return v.hidden ? null : v.textContent;"),
      readSummary(dir + "/run")["verdict"]["headline"]);
  const double t_start = logged.q.begin()->first, t_later = loggedTimeNear(logged, 0.35);
  const TipCheck start = drawnTip(browser, *s.robotModel(), logged, t_start);
  const TipCheck later = drawnTip(browser, *s.robotModel(), logged, t_later);
  // The arm moved on the screen between the two: a page that drew one pose
  // for both would fail one of the checks above.
  EXPECT_GT(std::hypot(start.expected_x - later.expected_x, start.expected_y - later.expected_y), 30.0);
  EXPECT_EQ(start.rotor_pixels, 0);  // a rigid arm has no rotors
  expectNoConsoleError(browser);
}

TEST(View, PlaySpeedPauseAndSeekMoveThePagesClockAsAsked) {
  const std::string dir = freshDir("view-clock");
  fs::create_directories(dir);
  const std::string log = inprocLog("rigid_2dof.yaml", dir, "--set duration=3");
  ViewServer server(log, dir);
  Browser browser(dir, 1000, 600);
  openViewer(browser, server);
  auto state = [&] { return browser.run("return window.lagrangeViewer.state();"); };
  auto setSpeed = [&](const std::string& speed) {
    browser.run(
        "const s = document.getElementById('speed'); s.value = arguments[0];"
        "s.dispatchEvent(new Event('change'));",
        {speed});
  };
  auto click = [&] { browser.run("document.getElementById('play').click();"); };
  // Simulated time advances by speed x the page's wall clock, to rounding.
  auto expectRate = [&](double speed) {
    ASSERT_TRUE(browser.waitUntil("window.lagrangeViewer.state().wall !== null", 5));
    const json a = state();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    const json b = state();
    ASSERT_TRUE(b["playing"].get<bool>());
    const double wall = (b["wall"].get<double>() - a["wall"].get<double>()) / 1000.0;
    ASSERT_GT(wall, 0.05);
    EXPECT_NEAR((b["t"].get<double>() - a["t"].get<double>()) / wall, speed, 1e-6 * speed);
  };
  EXPECT_FALSE(state()["playing"].get<bool>());
  setSpeed("4");
  click();
  expectRate(4.0);
  setSpeed("0.25");
  expectRate(0.25);
  click();  // pause
  const double paused_at = state()["t"].get<double>();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_FALSE(state()["playing"].get<bool>());
  EXPECT_EQ(state()["t"].get<double>(), paused_at);
  // Seek: the frame drawn is the last at or before the time sought.
  const json sought = seekTo(browser, 1.2345);
  EXPECT_EQ(sought["t"].get<double>(), 1.2345);
  EXPECT_EQ(browser.run("return window.lagrangeViewer.state().index;"), sought["index"]);
  EXPECT_LE(sought["frameT"].get<double>(), 1.2345);
  EXPECT_GT(sought["frameT"].get<double>(), 1.2345 - 0.0011);  // rigid_2dof: 1 kHz
  EXPECT_TRUE(
      browser.waitUntil("document.getElementById('time').textContent === 't = 1.234 s' || "
                        "document.getElementById('time').textContent === 't = 1.235 s'",
                        5))
      << browser.run("return document.getElementById('time').textContent;");
  // Played to the end at 10x, the page stops there.
  seekTo(browser, 2.9);
  setSpeed("10");
  click();
  ASSERT_TRUE(browser.waitUntil("!window.lagrangeViewer.state().playing", 5));
  const json end = state();
  EXPECT_EQ(end["t"].get<double>(), end["tEnd"].get<double>());
  expectNoConsoleError(browser);
}

TEST(View, AUrdfArmAndFlexibleJointsAreDrawnFromTheirLogs) {
  const std::string dir = freshDir("view-kinds");
  fs::create_directories(dir);
  {
    const std::string log = inprocLog("panda_theorem1.yaml", dir + "/panda", "--set duration=0.3");
    const Logged logged = readLogged(log);
    const config::Scenario s = config::loadScenario(kConfigs + "/panda_theorem1.yaml");
    ViewServer server(log, dir + "/panda");
    Browser browser(dir + "/panda", 1280, 720);
    openViewer(browser, server);
    const TipCheck c = drawnTip(browser, *s.robotModel(), logged, loggedTimeNear(logged, 0.2));
    const json base = browser.run("return window.lagrangeViewer.project([0, 0, 0]);");
    // The tip is away from the base on the screen, so a drawing of the base would fail.
    EXPECT_GT(std::hypot(c.expected_x - base[0].get<double>(), c.expected_y - base[1].get<double>()), 50.0);
    expectNoConsoleError(browser);
  }
  {
    const std::string log = inprocLog("flexible_2dof.yaml", dir + "/flexible", "--set duration=1");
    const Logged logged = readLogged(log);
    ASSERT_FALSE(logged.motor.empty());
    const config::Scenario s = config::loadScenario(kConfigs + "/flexible_2dof.yaml");
    ViewServer server(log, dir + "/flexible");
    Browser browser(dir + "/flexible", 1280, 720);
    openViewer(browser, server);
    const char* keep = std::getenv("LAGRANGE_VIEW_SCREENSHOT");
    const TipCheck c =
        drawnTip(browser, *s.robotModel(), logged, loggedTimeNear(logged, 0.15), keep ? keep : "");
    EXPECT_GT(c.rotor_pixels, 20) << "the rotors' pointers are not drawn";
    EXPECT_EQ(browser.run("return document.getElementById('legend-rotor').hidden;"), false)
        << "elastic joints: the legend names the rotors";
    expectNoConsoleError(browser);
  }
}

// The headless screenshot docs/viewer.md gives (tools/view/screenshot.py):
// it waits for <body data-ready>, seeks, and the picture holds the arm --
// the tip and the rotors' pointers in their colours -- not the blank page a
// screenshot at load shows. A URL nothing serves is named, exit 1.
TEST(View, TheDocumentedHeadlessScreenshotWaitsForTheDrawnArm) {
  const std::string dir = freshDir("view-screenshot");
  fs::create_directories(dir);
  ViewServer server(kGoldenDir + "flexible_2dof_filtered_rate_lockstep.lcm", dir);
  ASSERT_FALSE(server.url().empty()) << server.output();
  const std::string script = std::string(LAGRANGE_SOURCE_DIR) + "/tools/view/screenshot.py",
                    png = dir + "/view.png";
  const RunResult shot = shell("/usr/bin/python3 " + quote(script) + " " + server.url() + " " + quote(png) +
                               " --at 0.15 --size 1000x600");
  ASSERT_EQ(shot.exit_code, 0) << shot.output;
  EXPECT_NE(shot.output.find("screenshot.py: wrote " + png), std::string::npos) << shot.output;
  std::ifstream in(png, std::ios::binary);
  const RgbaImage image = decodePng(std::string(std::istreambuf_iterator<char>(in), {}));
  EXPECT_EQ(image.width, 1000);
  EXPECT_GT(findColour(image, kTipRgb[0], kTipRgb[1], kTipRgb[2], 40, 0, 0, image.width, image.height).count,
            20);
  EXPECT_GT(
      findColour(image, kRotorRgb[0], kRotorRgb[1], kRotorRgb[2], 40, 0, 0, image.width, image.height).count,
      20);
  EXPECT_EQ(server.stop(), 0);
  const RunResult none = shell("/usr/bin/python3 " + quote(script) + " " + server.url() + " " +
                               quote(dir + "/none.png") + " --timeout 5");
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_NE(none.output.find("cannot open " + server.url()), std::string::npos) << none.output;
  EXPECT_FALSE(fs::exists(dir + "/none.png"));
}

// A log longer than the page is sent whole (41 001 frames, sent as every
// 3rd): the torque plot still spans every logged torque to its extremes --
// the frames between those sent come as an envelope, and each pixel column
// draws its min and max rather than one sample of many. A rigid arm's legend
// names no rotor.
TEST(View, ItsPlotsKeepEveryPeakAndNameOnlyWhatTheArmHas) {
  const std::string dir = freshDir("view-peaks");
  fs::create_directories(dir);
  const std::string log = inprocLog("rigid_2dof.yaml", dir, "--set duration=41");
  const auto truth = readTruth(log);
  ASSERT_EQ(truth.size(), 41001u);
  double lo = truth[0].tau.minCoeff(), hi = truth[0].tau.maxCoeff();
  double sent_lo = lo, sent_hi = hi;
  for (size_t i = 0; i < truth.size(); ++i) {
    lo = std::min(lo, truth[i].tau.minCoeff()), hi = std::max(hi, truth[i].tau.maxCoeff());
    if (i % 3 == 0)
      sent_lo = std::min(sent_lo, truth[i].tau.minCoeff()),
      sent_hi = std::max(sent_hi, truth[i].tau.maxCoeff());
  }
  // The check can fail: an extreme lies on a frame the page is not sent.
  ASSERT_TRUE(sent_lo != lo || sent_hi != hi) << "every extreme is on a sent frame; pick another duration";
  ViewServer server(log, dir);
  Browser browser(dir, 1280, 720);
  openViewer(browser, server);
  const json extents = browser.run("return window.lagrangeViewer.plotExtents();");
  ASSERT_TRUE(extents["torque"].is_array()) << extents.dump();
  EXPECT_EQ(extents["torque"][0].get<double>(), lo);
  EXPECT_EQ(extents["torque"][1].get<double>(), hi);
  EXPECT_EQ(browser.run("return document.getElementById('legend-rotor').hidden;"), true);
  EXPECT_EQ(browser.run("return document.getElementById('torque-plot').title;"), "τ1: joint1\nτ2: joint2");
  expectNoConsoleError(browser);
}

// The run is long enough to outlast every allowance below (lcm.json 20 s, the
// viewer 30 s, the browser 20 s + its session, the page 30 s + 20 s): on CI a
// slow browser start once let a 60 s run end before the page's first look,
// and the page then rightly stood still. It is interrupted long before.
TEST(View, FollowsARunningScenarioLive) {
  const std::string dir = freshDir("view-live");
  fs::create_directories(dir);
  const std::string out = dir + "/run";
  Child run({kBin + "/lagrange", "run", kConfigs + "/rigid_2dof.yaml", "--out", out, "--set", "mode=realtime",
             "--set", "duration=200", "-q"},
            dir + "/run.out");
  ASSERT_TRUE(waitFor([&] { return fs::exists(out + "/lcm.json"); }, 20)) << slurp(dir + "/run.out");
  ViewServer server(out, dir);
  EXPECT_NE(server.output().find("the running scenario in"), std::string::npos) << server.output();
  Browser browser(dir, 1000, 600);
  openViewer(browser, server);
  ASSERT_TRUE(browser.waitUntil(
      "window.lagrangeViewer.state().described && window.lagrangeViewer.state().frames > 0", 20));
  const json a = browser.run("return window.lagrangeViewer.state();");
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  const json b = browser.run("return window.lagrangeViewer.state();");
  ASSERT_TRUE(run.running()) << "the run ended before the page was looked at; " << slurp(dir + "/run.out");
  EXPECT_EQ(b["mode"], "live");
  EXPECT_TRUE(b["follow"].get<bool>());
  EXPECT_GT(b["t"].get<double>(), a["t"].get<double>()) << "the page does not follow the run";
  EXPECT_GT(b["frames"].get<int>(), a["frames"].get<int>());
  // Following, it has drawn at least the newest frame it held a second ago
  // (frames that came after its last animation frame wait for the next).
  EXPECT_GE(b["t"].get<double>(), a["tEnd"].get<double>());
  // Stopped, the run keeps its log; a frame the page received is the log's, bit for bit.
  run.signal(SIGINT);
  ASSERT_EQ(run.wait(30), 130) << slurp(dir + "/run.out");
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const double end = browser.run("return window.lagrangeViewer.state().tEnd;").get<double>();
  const json back = seekTo(browser, end - 0.5);
  EXPECT_FALSE(back["follow"].get<bool>());  // seeking stops following
  const Logged logged = readLogged(out + "/run.lcm");
  ASSERT_TRUE(logged.q.count(back["frameT"].get<double>())) << back.dump();
  EXPECT_EQ(back["q"].get<std::vector<double>>(), logged.q.at(back["frameT"].get<double>()));
  expectNoConsoleError(browser);
  EXPECT_EQ(server.stop(), 0) << server.output();
}

// The port a viewer printed in its URL (`url` captures it) within 30 s, or "".
std::string servedPort(const std::string& output, const std::string& url) {
  const std::regex pattern(url);
  std::string port;
  waitFor(
      [&] {
        std::smatch m;
        const std::string text = slurp(output);
        if (std::regex_search(text, m, pattern)) port = m[1];
        return !port.empty();
      },
      30);
  return port;
}

TEST(View, RefusesANonLoopbackAddressUnlessAskedAndNamesBadSources) {
  const std::string dir = freshDir("view-bind");
  fs::create_directories(dir);
  const std::string log = std::string(LAGRANGE_SOURCE_DIR) + "/tests/data/golden/rigid_2dof_lockstep.lcm";
  const RunResult refused = lagrange("view " + quote(log) + " --host 0.0.0.0 --port 0");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--allow-remote"), std::string::npos) << refused.output;
  EXPECT_EQ(refused.output.find("http://"), std::string::npos) << refused.output;
  {
    // Asked: it serves on every address of the (test's private) network.
    const std::string output = dir + "/remote.out";
    Child remote({kBin + "/lagrange", "view", log, "--host", "0.0.0.0", "--port", "0", "--allow-remote"},
                 output);
    const std::string port = servedPort(output, R"(http://0\.0\.0\.0:([0-9]+)/)");
    ASSERT_FALSE(port.empty()) << slurp(output);
    // The golden log as it is.
    httplib::Client client("127.0.0.1", std::stoi(port));
    const auto api = client.Get("/api/log");
    ASSERT_TRUE(api);
    EXPECT_EQ(json::parse(api->body)["description"]["kind"], "planar_chain") << api->body.substr(0, 300);
    remote.signal(SIGTERM);
    EXPECT_EQ(remote.wait(10), 0);
  }
  {
    // A log from before ROBOT_DESCRIPTION (the golden log without it): its
    // arm comes from its SCENARIO, and the viewer says so.
    const std::string old_log = dir + "/no-description.lcm";
    {
      lcm::LogFile in(log, "r"), out(old_log, "w");
      while (const lcm::LogEvent* ev = in.readNextEvent())
        if (ev->channel != "ROBOT_DESCRIPTION") out.writeEvent(const_cast<lcm::LogEvent*>(ev));
    }
    const std::string output = dir + "/old.out";
    Child old({kBin + "/lagrange", "view", old_log, "--port", "0"}, output);
    const std::string port = servedPort(output, R"(http://127\.0\.0\.1:([0-9]+)/)");
    ASSERT_FALSE(port.empty()) << slurp(output);
    httplib::Client client("127.0.0.1", std::stoi(port));
    const auto api = client.Get("/api/log");
    ASSERT_TRUE(api);
    EXPECT_EQ(json::parse(api->body)["description"]["kind"], "planar_chain") << api->body.substr(0, 300);
    EXPECT_NE(slurp(output).find("drawn from its SCENARIO"), std::string::npos) << slurp(output);
    old.signal(SIGTERM);
    EXPECT_EQ(old.wait(10), 0);
  }
  {
    // A finished run whose launcher's pid now belongs to another program
    // (this test): its log is drawn, not a dead bus followed.
    fs::create_directories(dir + "/stale");
    fs::copy_file(log, dir + "/stale/run.lcm");
    std::ofstream(dir + "/stale/lcm.json") << json{
        {"lcm_url", "udpm://239.255.76.67:7667?ttl=0"},
        {"run_id", 1},
        {"netns_pid", nullptr},
        {"launcher_pid", getpid()}}.dump();
    ViewServer stale(dir + "/stale", dir + "/stale");
    EXPECT_NE(stale.output().find("stale/run.lcm at http://127.0.0.1:"), std::string::npos) << stale.output();
    EXPECT_EQ(stale.stop(), 0);
  }
  const RunResult missing = lagrange("view " + quote(dir + "/nothing.lcm"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("does not exist; expected a run's output directory or a log file"),
            std::string::npos)
      << missing.output;
  std::ofstream(dir + "/not-a-log.lcm") << "not a log";
  const RunResult garbage = lagrange("view " + quote(dir + "/not-a-log.lcm"));
  EXPECT_EQ(garbage.exit_code, 2) << garbage.output;
}

}  // namespace
}  // namespace lagrange::testing
