// `lagrange view` survives its visitors: idle TCP connections and open live
// streams do not starve page loads, idle connections are closed, a flood of
// connections beyond the limit is refused at once (503) instead of queued,
// a request whose Host header is not a name of the viewer (DNS rebinding)
// is refused with 421, and no request makes it hold more than its limits:
// a body past 4 KiB or without a length is refused unread, a head past 64
// KiB ends the connection, Range headers are ignored. Plain sockets: no
// browser needed.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "support/child.hpp"
#include "support/configs.hpp"
#include "support/launch.hpp"
#include "support/wait.hpp"

namespace lagrange::testing {
namespace {

using Clock = std::chrono::steady_clock;

// `lagrange view ARGS --port 0` in the background, and the port it printed.
class Viewer {
 public:
  explicit Viewer(const std::vector<std::string>& args, const std::string& url_host = R"(127\.0\.0\.1)")
      : output_(freshDir("view-guard") + ".out"), child_(argv(args), output_) {
    const std::regex url("http://" + url_host + ":([0-9]+)/");
    waitFor(
        [&] {
          std::smatch m;
          const std::string text = slurp(output_);
          if (std::regex_search(text, m, url)) port_ = std::stoi(m[1]);
          return port_ > 0 || !child_.running();
        },
        30);
  }
  ~Viewer() { child_.signal(SIGTERM); }
  int port() const { return port_; }
  std::string output() const { return slurp(output_); }
  int stop() {
    child_.signal(SIGTERM);
    return child_.wait(10);
  }

 private:
  static std::vector<std::string> argv(const std::vector<std::string>& args) {
    std::vector<std::string> all = {kBin + "/lagrange", "view"};
    all.insert(all.end(), args.begin(), args.end());
    all.insert(all.end(), {"--port", "0"});
    return all;
  }
  std::string output_;
  Child child_;
  int port_ = 0;
};

// A TCP connection to 127.0.0.1:port, closed with the object.
class Connection {
 public:
  explicit Connection(int port) : fd_(socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = connect(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~Connection() { close(fd_); }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  bool connected() const { return connected_; }
  void send(const std::string& bytes) { (void)::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL); }
  /// What arrives within `seconds`, until `enough` is in it or the server closes.
  std::string receive(double seconds, const std::string& enough = "") {
    const auto end =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
    while (Clock::now() < end && (enough.empty() || received_.find(enough) == std::string::npos)) {
      pollfd p{fd_, POLLIN, 0};
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
      if (poll(&p, 1, static_cast<int>(std::max<long long>(1, left))) <= 0) continue;
      char buf[4096];
      const ssize_t got = recv(fd_, buf, sizeof buf, 0);
      if (got <= 0) {
        closed_ = true;
        break;
      }
      received_.append(buf, static_cast<std::size_t>(got));
    }
    return received_;
  }
  /// The server closed the connection (seen by receive).
  bool closedByServer() const { return closed_; }

 private:
  int fd_;
  bool connected_ = false;
  bool closed_ = false;
  std::string received_;
};

std::string get(const std::string& path, const std::string& host, bool keep_alive = false) {
  std::string request = "GET " + path + " HTTP/1.1\r\n";
  if (!host.empty()) request += "Host: " + host + "\r\n";
  return request + (keep_alive ? "" : "Connection: close\r\n") + "\r\n";
}

struct Answer {
  std::string text;
  double seconds;
};

// A whole request and answer on a connection of its own, timed.
Answer ask(int port, const std::string& path, const std::string& host, double timeout = 5) {
  const auto start = Clock::now();
  Connection c(port);
  c.send(get(path, host));
  Answer a;
  a.text = c.receive(timeout);
  a.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return a;
}

std::string freshLcmUrl() {
  std::mt19937 rng(std::random_device{}());
  return "udpm://239.255.76.67:" + std::to_string(20000 + rng() % 20000) + "?ttl=0";
}

TEST(ViewGuard, IdleConnectionsAndOpenLiveStreamsDoNotStarvePageLoads) {
  Viewer viewer({"--lcm-url", freshLcmUrl()});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string host = "127.0.0.1:" + std::to_string(viewer.port());
  std::vector<std::unique_ptr<Connection>> idle, streams;
  for (int i = 0; i < 20; ++i) {
    idle.push_back(std::make_unique<Connection>(viewer.port()));
    ASSERT_TRUE(idle.back()->connected());
  }
  // 16 live streams, the limit: each is open (its headers and a first event
  // came) and holds its connection.
  for (int i = 0; i < 16; ++i) {
    streams.push_back(std::make_unique<Connection>(viewer.port()));
    streams.back()->send(get("/api/live", host, true));
    EXPECT_NE(streams.back()->receive(5, "\n\n").find("text/event-stream"), std::string::npos)
        << "stream " << i << ": " << streams.back()->receive(0);
  }
  // With 20 idle connections and 16 streams open, a page loads at once: the
  // stock server's 8 workers would all be held.
  const Answer page = ask(viewer.port(), "/", host);
  EXPECT_EQ(page.text.rfind("HTTP/1.1 200", 0), 0u) << page.text.substr(0, 200);
  EXPECT_LT(page.seconds, 2.0);
  for (auto& c : idle) {  // they were all still open when the page loaded
    c->receive(0.001);
    EXPECT_FALSE(c->closedByServer());
  }
  const Answer session = ask(viewer.port(), "/api/session", host);
  EXPECT_NE(session.text.find("\"mode\":\"live\""), std::string::npos) << session.text;
  EXPECT_LT(session.seconds, 2.0);
  // A 17th stream is refused at once, and says why.
  const Answer extra = ask(viewer.port(), "/api/live", host);
  EXPECT_EQ(extra.text.rfind("HTTP/1.1 503", 0), 0u) << extra.text;
  EXPECT_NE(extra.text.find("16 live streams open, its limit"), std::string::npos) << extra.text;
  EXPECT_LT(extra.seconds, 2.0);

  // The idle connections are closed by the server (2 s idle timeout)...
  for (auto& c : idle) {
    EXPECT_EQ(c->receive(5), "");
    EXPECT_TRUE(c->closedByServer());
  }
  // ...the streams are not: they still receive.
  for (auto& s : streams) {
    const std::size_t before = s->receive(0).size();
    EXPECT_GT(s->receive(0.3).size(), before);
    EXPECT_FALSE(s->closedByServer());
  }
  // A closed stream frees its place.
  streams.pop_back();
  EXPECT_TRUE(waitFor(
      [&] {
        Connection again(viewer.port());
        again.send(get("/api/live", host, true));
        return again.receive(2, "\n\n").find("text/event-stream") != std::string::npos;
      },
      10));
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

TEST(ViewGuard, AFloodOfConnectionsIsRefusedAtOnceAndTheViewerRecovers) {
  Viewer viewer({kGoldenRigidLockstep});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string host = "127.0.0.1:" + std::to_string(viewer.port());
  std::vector<std::unique_ptr<Connection>> flood;
  for (int i = 0; i < 60; ++i) flood.push_back(std::make_unique<Connection>(viewer.port()));
  // 48 are admitted (and wait for a request); the other 12 are answered 503
  // and closed at once, well within the admitted ones' 2 s idle timeout.
  const auto refusals = [&] {
    int n = 0;
    for (auto& c : flood) {
      const std::string got = c->receive(0.001, "\n\n");
      n += got.rfind("HTTP/1.1 503", 0) == 0 &&
           got.find("48 connections open, its limit") != std::string::npos;
    }
    return n;
  };
  const auto flooded = Clock::now();
  EXPECT_TRUE(waitFor([&] { return refusals() == 12; }, 1.0));
  // A request during the flood is refused at once too, not queued behind it.
  const Answer during = ask(viewer.port(), "/api/session", host);
  EXPECT_EQ(during.text.rfind("HTTP/1.1 503", 0), 0u) << during.text;
  EXPECT_LT(during.seconds, 1.0);
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - flooded).count(), 2.0) << "the flood was still open";
  EXPECT_EQ(refusals(), 12);  // and no admitted connection was refused later
  // Once the idle ones have timed out, pages load again.
  EXPECT_TRUE(waitFor(
      [&] { return ask(viewer.port(), "/api/session", host).text.rfind("HTTP/1.1 200", 0) == 0; }, 5));
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

TEST(ViewGuard, AForeignHostHeaderIsRefusedAsDnsRebinding) {
  Viewer viewer({kGoldenRigidLockstep});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string port = std::to_string(viewer.port());
  for (const std::string& host :
       std::vector<std::string>{"127.0.0.1:" + port, "127.0.0.1", "localhost:" + port, "LocalHost",
                                "[::1]:" + port, "localhost:9000" /* an ssh -L tunnel's port */}) {
    const Answer a = ask(viewer.port(), "/api/session", host);
    EXPECT_EQ(a.text.rfind("HTTP/1.1 200", 0), 0u) << host << ": " << a.text;
  }
  for (const std::string& host :
       std::vector<std::string>{"evil.example:" + port, "evil.example", "127.0.0.1.evil.example:" + port,
                                "localhost.evil.example", "localhost:abc", "[::1"}) {
    const Answer a = ask(viewer.port(), "/api/log", host);
    EXPECT_EQ(a.text.rfind("HTTP/1.1 421", 0), 0u) << host << ": " << a.text;
    EXPECT_NE(a.text.find("expected one of 127.0.0.1, [::1], localhost (with or without a port)"),
              std::string::npos)
        << a.text;
    EXPECT_EQ(a.text.find("\"frames\""), std::string::npos) << host << ": the log was served";
  }
  EXPECT_NE(ask(viewer.port(), "/", "evil.example").text.find("DNS rebinding"), std::string::npos);
  const Answer none = ask(viewer.port(), "/api/session", "");  // no Host header at all
  EXPECT_EQ(none.text.rfind("HTTP/1.1 421", 0), 0u) << none.text;
  EXPECT_NE(none.text.find("no Host header"), std::string::npos) << none.text;
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

// --allow-remote on every address: this machine's name is answered too,
// other names still are not.
TEST(ViewGuard, AllowRemoteAcceptsThisMachinesNameAndStillRefusesOthers) {
  Viewer viewer({kGoldenRigidLockstep, "--host", "0.0.0.0", "--allow-remote"}, R"(0\.0\.0\.0)");
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  char name[256] = {};
  ASSERT_EQ(gethostname(name, sizeof name - 1), 0);
  const std::string port = std::to_string(viewer.port());
  const Answer own = ask(viewer.port(), "/api/session", std::string(name) + ":" + port);
  EXPECT_EQ(own.text.rfind("HTTP/1.1 200", 0), 0u) << name << ": " << own.text;
  const Answer other = ask(viewer.port(), "/api/session", "evil.example:" + port);
  EXPECT_EQ(other.text.rfind("HTTP/1.1 421", 0), 0u) << other.text;
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

// The status code of an HTTP answer ("HTTP/1.1 413 ..." -> 413), 0 if none.
int statusOf(const std::string& answer) {
  return answer.rfind("HTTP/1.1 ", 0) == 0 ? std::atoi(answer.c_str() + 9) : 0;
}

// The Content-Length an answer declares, -1 if none.
long long contentLengthOf(const std::string& answer) {
  const std::size_t at = answer.find("Content-Length: ");
  return at == std::string::npos ? -1 : std::atoll(answer.c_str() + at + 16);
}

// A POST announcing 2 GB: before, the viewer read the whole body into memory
// (2.1 GB for one client, up to 48 at once) and only then answered. Now it
// answers 413 at once, reads none of it, and closes the connection; a body
// without a length gets 411 the same way. The viewer still serves after.
TEST(ViewGuard, ARequestBodyPastTheLimitIsRefusedUnreadAndTheConnectionClosed) {
  Viewer viewer({kGoldenRigidLockstep});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string host = "127.0.0.1:" + std::to_string(viewer.port());
  {
    const auto start = Clock::now();
    Connection c(viewer.port());
    c.send("POST /api/log HTTP/1.1\r\nHost: " + host + "\r\nContent-Length: 2000000000\r\n\r\n" +
           std::string(1 << 16, 'x'));
    const std::string answer = c.receive(3);
    EXPECT_EQ(statusOf(answer), 413) << answer.substr(0, 300);
    EXPECT_NE(answer.find("a request body of 2000000000 bytes; the viewer takes at most 4096 bytes"),
              std::string::npos)
        << answer.substr(0, 300);
    EXPECT_NE(answer.find("Connection: close"), std::string::npos) << answer.substr(0, 300);
    EXPECT_TRUE(c.closedByServer());
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
  }
  {
    Connection c(viewer.port());
    c.send("POST / HTTP/1.1\r\nHost: " + host + "\r\nTransfer-Encoding: chunked\r\n\r\n10000\r\n" +
           std::string(1 << 16, 'x'));
    const std::string answer = c.receive(3);
    EXPECT_EQ(statusOf(answer), 411) << answer.substr(0, 300);
    EXPECT_TRUE(c.closedByServer());
  }
  for (const char* length : {"-1", "12abc", "99999999999999999999999"}) {
    Connection c(viewer.port());
    c.send("POST / HTTP/1.1\r\nHost: " + host + "\r\nContent-Length: " + length + "\r\n\r\n");
    const std::string answer = c.receive(3);
    EXPECT_EQ(statusOf(answer), 400) << length << ": " << answer.substr(0, 300);
    EXPECT_NE(answer.find("is not one length in bytes"), std::string::npos) << answer.substr(0, 300);
  }
  // A GET with a small body is answered, and its connection closed: what is
  // left of the body is never taken for a request.
  {
    Connection c(viewer.port());
    c.send("GET /api/session HTTP/1.1\r\nHost: " + host + "\r\nContent-Length: 40\r\n\r\n" +
           "GET /api/log HTTP/1.1\r\nHost: x\r\n\r\n");
    const std::string answer = c.receive(3);
    EXPECT_EQ(statusOf(answer), 200) << answer.substr(0, 300);
    EXPECT_EQ(answer.find("HTTP/1.1", 8), std::string::npos) << "a second answer: " << answer;
    EXPECT_TRUE(c.closedByServer());
  }
  EXPECT_EQ(statusOf(ask(viewer.port(), "/api/session", host).text), 200);
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

// 2 000 ranges of /api/log in a 6 kB request were answered with 313 MB (a
// copy of the log's frames per range). Range is ignored now: the answer is
// the whole resource, once, as a plain GET gets it.
TEST(ViewGuard, ManyRangesGetTheWholeBodyOnce) {
  Viewer viewer({kGoldenRigidLockstep});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string host = "127.0.0.1:" + std::to_string(viewer.port());
  const Answer plain = ask(viewer.port(), "/api/log", host);
  ASSERT_EQ(statusOf(plain.text), 200) << plain.text.substr(0, 300);
  const long long whole = contentLengthOf(plain.text);
  ASSERT_GT(whole, 1000);
  std::string ranges = "bytes=0-";
  for (int i = 1; i < 2000; ++i) ranges += ",0-";
  Connection c(viewer.port());
  c.send("GET /api/log HTTP/1.1\r\nHost: " + host + "\r\nRange: " + ranges + "\r\nConnection: close\r\n\r\n");
  const std::string answer = c.receive(10);
  EXPECT_EQ(statusOf(answer), 200) << answer.substr(0, 300);
  EXPECT_EQ(contentLengthOf(answer), whole);
  EXPECT_LT(answer.size(), static_cast<std::size_t>(whole) + 1000);
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

// A request's line and headers may take 64 KiB: a flood of header lines (1
// MB, each line short) ends the connection there instead of being held.
TEST(ViewGuard, AHeadPastItsLimitEndsTheConnection) {
  Viewer viewer({kGoldenRigidLockstep});
  ASSERT_GT(viewer.port(), 0) << viewer.output();
  const std::string host = "127.0.0.1:" + std::to_string(viewer.port());
  std::string flood = "GET /api/session HTTP/1.1\r\nHost: " + host + "\r\n";
  for (int i = 0; i < 50000; ++i) flood += "X-Filler: " + std::to_string(i) + "\r\n";
  Connection c(viewer.port());
  c.send(flood + "\r\n");
  const std::string answer = c.receive(5);
  EXPECT_EQ(statusOf(answer), 400) << answer.substr(0, 300);
  EXPECT_TRUE(c.closedByServer());
  EXPECT_EQ(statusOf(ask(viewer.port(), "/api/session", host).text), 200);
  EXPECT_EQ(viewer.stop(), 0) << viewer.output();
}

}  // namespace
}  // namespace lagrange::testing
