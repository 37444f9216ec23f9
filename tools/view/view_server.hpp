#pragma once
/// @file
/// The viewer's HTTP server: cpp-httplib's, with its connections bounded and
/// timed. Stock cpp-httplib 0.11 (Debian 12) serves each connection on one
/// of 8 pooled threads for as long as it stays open, and queues the rest
/// without bound: eight idle TCP connections, or eight open live streams
/// (Server-Sent Events), held every worker and every other visitor waited.
///
/// Here every connection admitted has a thread of its own (the pool has one
/// per admitted connection, and spares), so no request waits behind another;
/// a connection that sends no request within `idle_timeout` (a first one, or
/// the next on a kept-alive connection) is closed, and one whose request is
/// not in within `request_timeout` of its first byte (a slow sender) is
/// dropped; beyond `max_connections` open at once a new connection is
/// answered 503 at once and closed, never queued. Live streams are bounded
/// separately (tryOpenStream), below max_connections, so open pages never
/// leave page loads without a connection.
///
/// What one request may make the server hold is bounded too. The library
/// reads a body of any length into memory before routing (a 2 GB POST took
/// the viewer to 2.1 GB, and 48 connections may be open), and answers a
/// Range header of any number of ranges, each a copy (2 000 ranges of
/// /api/log in a 6 kB request: 313 MB sent). Here a request's line and
/// headers may take at most max_head_bytes; a body is refused before a byte
/// of it is read when it is longer than max_body_bytes (413) or has no
/// length (chunked: 411), and the connection of any request with a body is
/// closed after the answer (the viewer's page sends none); Range headers are
/// ignored, every answer is the whole resource (RFC 9110 lets a server).

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>

namespace lagrange::tools {

struct ServerLimits {
  int max_connections = 48;                         ///< open at once; more are refused with 503 at once
  int max_live_streams = 16;                        ///< of them, open live streams (SSE); more get 503
  std::chrono::milliseconds idle_timeout{2000};     ///< for a request to start coming
  std::chrono::milliseconds request_timeout{5000};  ///< for its line and headers, once started
  std::chrono::milliseconds write_timeout{5000};    ///< for a client to take each write
  std::size_t max_head_bytes = 64 * 1024;           ///< a request's line and headers, read before routing
  std::size_t max_body_bytes = 4096;                ///< a request body; larger is refused unread (413)
};

class GuardedHttpServer : public httplib::Server {
 public:
  explicit GuardedHttpServer(const ServerLimits& limits = {});

  /// The application's own check of each request before it is routed (the
  /// Host header, view.cpp), after the server's body limit. Hides the
  /// library's setter, which would drop that limit.
  GuardedHttpServer& set_pre_routing_handler(HandlerWithResponse handler);

  /// Binds to host:port (0: any free port) with a backlog for bursts of
  /// connections; the port, or -1.
  int bindPort(const std::string& host, int port);

  /// A live stream's place, released when the token is destroyed; nullptr
  /// if max_live_streams are open.
  std::shared_ptr<void> tryOpenStream();

  const ServerLimits& limits() const { return limits_; }
  /// Connections refused so far because max_connections were open.
  long long refusedConnections() const { return refused_; }

 private:
  // cpp-httplib's own per-connection loop, with the admission and the
  // timeouts above (overrides the library's, which has neither).
  bool process_and_close_socket(socket_t sock) override;
  bool waitForRequest(socket_t sock) const;

  ServerLimits limits_;
  HandlerWithResponse request_check_;
  std::atomic<int> open_{0};
  std::atomic<int> streams_{0};
  std::atomic<long long> refused_{0};
};

}  // namespace lagrange::tools
