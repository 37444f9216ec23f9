#pragma once
/// @file
/// `lagrange view [RUN_DIR | LOG] [--host H] [--port P] [--allow-remote]
/// [--lcm-url URL]`: a local web page that draws the arm in 3D, the
/// reference as a ghost arm, flexible joints' rotor angles, and plots of
/// |q~| and the torques -- from a log (play, pause, speed, seek) or live from
/// a running scenario (joining its network namespace as `lagrange spy` does).
///
/// The HTTP server is cpp-httplib (Debian's libcpp-httplib-dev): a small
/// threaded server with static files, chunked responses (the live stream is
/// Server-Sent Events over one of them) and bind-then-listen, which lets the
/// socket be opened in this machine's network namespace before the process
/// joins a run's private one. The page uses three.js from Debian's
/// libjs-three, served from /usr/share/javascript/three: nothing is fetched
/// from the network at view time.

#include <string>

#include "tools/subcommand.hpp"

namespace lagrange::tools {

struct ViewOptions {
  std::string source;  ///< a run's output directory or a log; empty: live on lcm_url
  std::string host = "127.0.0.1";
  int port = 8642;  ///< 0: any free port
  bool allow_remote = false;
  std::string lcm_url;   ///< live on this URL (overrides a run directory's)
  std::string key_file;  ///< live: the run's key (default: a running run directory's run.key)
};

/// True for 127.0.0.0/8, ::1 and "localhost".
bool isLoopbackHost(const std::string& host);

/// Serves until SIGINT or SIGTERM; returns the exit code (2: bad options or source).
int runView(const ViewOptions& options);

/// Declares `view` and its options on the front end (tools/view/view_cli.cpp).
Subcommand addViewCommand(CLI::App& app);

}  // namespace lagrange::tools
