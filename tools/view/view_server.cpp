#include "tools/view/view_server.hpp"

#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <string>
#include <utility>

namespace lagrange::tools {

namespace {

using Clock = std::chrono::steady_clock;

// Threads beyond max_connections: they only refuse (a write and a close),
// so a flood is answered at once instead of waiting for a worker.
constexpr int kRefusingWorkers = 16;

// Waits up to `timeout` for `events` on the socket (a negative timeout: not at all).
bool waitFor(socket_t sock, short events, std::chrono::milliseconds timeout) {
  pollfd p{sock, events, 0};
  for (;;) {
    const int ready = poll(&p, 1, static_cast<int>(std::max<long long>(0, timeout.count())));
    if (ready < 0 && errno == EINTR) continue;
    return ready > 0 && (p.revents & (events | POLLHUP | POLLERR)) != 0;
  }
}

void addressOf(int (*get)(int, sockaddr*, socklen_t*), socket_t sock, std::string& ip, int& port) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  char host[NI_MAXHOST] = {}, service[NI_MAXSERV] = {};
  if (get(sock, reinterpret_cast<sockaddr*>(&address), &length) != 0 ||
      getnameinfo(reinterpret_cast<sockaddr*>(&address), length, host, sizeof host, service, sizeof service,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return;
  ip = host;
  port = std::atoi(service);
}

// One request's view of a connection, as cpp-httplib's own SocketStream
// (not in Debian's header), but reading only until a deadline -- a client
// that trickles its request a byte at a time loses the connection at it --
// and at most `max_read` bytes: a flood of header lines ends there (the
// library answers 400), and no body longer than the limit is ever read.
class DeadlineSocketStream : public httplib::Stream {
 public:
  DeadlineSocketStream(socket_t sock, Clock::time_point read_deadline,
                       std::chrono::milliseconds write_timeout, std::size_t max_read)
      : sock_(sock), read_deadline_(read_deadline), write_timeout_(write_timeout), left_(max_read) {}

  bool is_readable() const override {
    return waitFor(sock_, POLLIN,
                   std::chrono::duration_cast<std::chrono::milliseconds>(read_deadline_ - Clock::now()));
  }
  bool is_writable() const override { return waitFor(sock_, POLLOUT, write_timeout_); }
  ssize_t read(char* ptr, size_t size) override {
    if (left_ == 0 || !is_readable()) return -1;
    ssize_t got;
    while ((got = recv(sock_, ptr, std::min(size, left_), 0)) < 0 && errno == EINTR) {
    }
    if (got > 0) left_ -= static_cast<std::size_t>(got);
    return got;
  }
  ssize_t write(const char* ptr, size_t size) override {
    if (!is_writable()) return -1;
    ssize_t sent;
    while ((sent = send(sock_, ptr, size, MSG_NOSIGNAL)) < 0 && errno == EINTR) {
    }
    return sent;
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    addressOf(getpeername, sock_, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    addressOf(getsockname, sock_, ip, port);
  }
  socket_t socket() const override { return sock_; }

 private:
  socket_t sock_;
  Clock::time_point read_deadline_;
  std::chrono::milliseconds write_timeout_;
  std::size_t left_;
};

// Why a request's body is refused before a byte of it is read: a status and
// a reason for the answer, or status 0. The viewer's page sends no body.
struct BodyRefusal {
  int status = 0;
  std::string reason;
};

BodyRefusal bodyRefusal(const httplib::Request& req, std::size_t max_body_bytes) {
  const std::string limit = std::to_string(max_body_bytes) + " bytes";
  if (req.has_header("Transfer-Encoding"))
    return {411, "a request body without a length (Transfer-Encoding: " +
                     req.get_header_value("Transfer-Encoding") +
                     "); the viewer takes a Content-Length of at most " + limit + ", and needs no body"};
  const std::size_t lengths = req.get_header_value_count("Content-Length");
  if (lengths == 0) return {};
  const std::string length = req.get_header_value("Content-Length");
  bool digits = !length.empty() && length.size() <= 19;
  for (const char c : length) digits = digits && c >= '0' && c <= '9';
  for (std::size_t i = 1; i < lengths; ++i)
    digits = digits && req.get_header_value("Content-Length", i) == length;
  if (!digits)
    return {400, "Content-Length '" + length + "'" +
                     (lengths > 1 ? " (given " + std::to_string(lengths) + " times)" : "") +
                     " is not one length in bytes; expected a number of at most " + limit};
  if (std::stoull(length) > max_body_bytes)
    return {413, "a request body of " + length + " bytes; the viewer takes at most " + limit +
                     " (its page sends none), and read none of it"};
  return {};
}

bool hasBody(const httplib::Request& req) {
  return req.has_header("Transfer-Encoding") ||
         (req.has_header("Content-Length") && req.get_header_value("Content-Length") != "0");
}

// 503 and close, without reading: the client learns at once to come back later.
void refuse(socket_t sock, int max_connections) {
  const std::string why = "the viewer has " + std::to_string(max_connections) +
                          " connections open, its limit; try again when some have closed\n";
  const std::string response =
      "HTTP/1.1 503 Service Unavailable\r\nContent-Type: text/plain\r\n"
      "Connection: close\r\nRetry-After: 2\r\nContent-Length: " +
      std::to_string(why.size()) + "\r\n\r\n" + why;
  (void)send(sock, response.data(), response.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
  shutdown(sock, SHUT_WR);
  // What the client already sent is read away: closing with unread bytes
  // would reset the connection, and the client could lose the answer.
  char sink[4096];
  for (int i = 0; i < 4 && recv(sock, sink, sizeof sink, MSG_DONTWAIT) > 0; ++i) {
  }
  close(sock);
}

}  // namespace

GuardedHttpServer::GuardedHttpServer(const ServerLimits& limits) : limits_(limits) {
  const size_t workers = static_cast<size_t>(limits_.max_connections + kRefusingWorkers);
  new_task_queue = [workers] { return new httplib::ThreadPool(workers); };
  const auto ms = [](std::chrono::milliseconds d) {
    return std::chrono::duration_cast<std::chrono::microseconds>(d);
  };
  set_read_timeout(ms(limits_.request_timeout));  // the library's, for what it reads itself
  set_write_timeout(ms(limits_.write_timeout));
  set_payload_max_length(limits_.max_body_bytes);  // what the library reads of a body it routes
  // Before routing, which would read the body: one too long, or of no length, is refused unread.
  httplib::Server::set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    const BodyRefusal refusal = bodyRefusal(req, limits_.max_body_bytes);
    if (refusal.status != 0) {
      res.status = refusal.status;
      res.set_content("lagrange view: " + refusal.reason + "\n", "text/plain");
      return HandlerResponse::Handled;
    }
    return request_check_ ? request_check_(req, res) : HandlerResponse::Unhandled;
  });
}

GuardedHttpServer& GuardedHttpServer::set_pre_routing_handler(HandlerWithResponse handler) {
  request_check_ = std::move(handler);
  return *this;
}

std::shared_ptr<void> GuardedHttpServer::tryOpenStream() {
  if (streams_.fetch_add(1) >= limits_.max_live_streams) {
    --streams_;
    return nullptr;
  }
  // Points at the server only to be non-null: the deleter frees the place, nothing else.
  return std::shared_ptr<void>(static_cast<void*>(this), [this](void*) { --streams_; });
}

int GuardedHttpServer::bindPort(const std::string& host, int port) {
  const int bound = port == 0 ? bind_to_any_port(host) : (bind_to_port(host, port) ? port : -1);
  // cpp-httplib 0.11 listens with a backlog of 5: connections beyond it wait
  // in the kernel, unanswered, for a SYN-ACK retransmission (1 s, 3 s, ...)
  // before this server can even refuse them. Listening again sets the backlog.
  if (bound >= 0) ::listen(svr_sock_, SOMAXCONN);
  return bound;
}

// Until a request starts to arrive (or the client closes), at most
// idle_timeout; early when the server stops.
bool GuardedHttpServer::waitForRequest(socket_t sock) const {
  const Clock::time_point end = Clock::now() + limits_.idle_timeout;
  for (Clock::time_point now = Clock::now(); now < end && svr_sock_ != INVALID_SOCKET; now = Clock::now()) {
    const auto slice = std::min<Clock::duration>(end - now, std::chrono::milliseconds(50));
    if (waitFor(sock, POLLIN, std::chrono::duration_cast<std::chrono::milliseconds>(slice))) return true;
  }
  return false;
}

bool GuardedHttpServer::process_and_close_socket(socket_t sock) {
  if (open_.fetch_add(1) >= limits_.max_connections) {
    --open_;
    ++refused_;
    refuse(sock, limits_.max_connections);
    return false;
  }
  bool served = false;
  for (size_t left = keep_alive_max_count_; left > 0 && waitForRequest(sock); --left) {
    DeadlineSocketStream stream(sock, Clock::now() + limits_.request_timeout, limits_.write_timeout,
                                limits_.max_head_bytes + limits_.max_body_bytes);
    bool closed_by_client = false, with_body = false;
    // Once the line and headers are in, before routing: the library has
    // parsed the ranges (a copy of the body each), and not read a body yet.
    const auto setup = [&with_body](httplib::Request& req) {
      req.ranges.clear();  // every answer whole: a Range header is ignored
      // A body is never read past the limit, and what is left of it must not
      // be taken for the next request: the answer closes the connection.
      if ((with_body = hasBody(req))) {
        req.headers.erase("Connection");
        req.set_header("Connection", "close");
      }
    };
    served = process_request(stream, left == 1, closed_by_client, setup);
    if (!served || closed_by_client || with_body) break;
  }
  shutdown(sock, SHUT_RDWR);
  close(sock);
  --open_;
  return served;
}

}  // namespace lagrange::tools
