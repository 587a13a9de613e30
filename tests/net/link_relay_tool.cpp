// link_relay: the link conditioner (fixstep/net/link_conditioner.hpp) as a program, so that scripts
// can put two processes of a game on either side of a bad link:
//
//   link_relay --upstream 127.0.0.1:7777 [--latency-ms 20] [--jitter-ms 5] [--loss 0.05]
//              [--duplicate 0.01] [--reorder 0.01] [--seed 1] [--port 0] [--port-file FILE]
//              [--seconds 60]
//
// The peers join the relay's port (printed, and written to --port-file) instead of upstream's.
// Runs until SIGINT / SIGTERM or --seconds have passed, then prints what the link did. A test
// helper: exit 2 for a bad command line, 1 when a socket cannot be bound.
#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fixstep/net/link_conditioner.hpp>
#include <fstream>
#include <string>
#include <thread>

namespace {

std::atomic<bool> stop{false};
extern "C" void on_signal(int) {
  stop = true;
}

fixstep::net::Address host_port(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) throw CLI::ValidationError("--upstream", "wants HOST:PORT");
  const int port = std::stoi(text.substr(colon + 1));
  if (port < 1 || port > 65535) throw CLI::ValidationError("--upstream", "PORT wants 1-65535");
  return {text.substr(0, colon), static_cast<std::uint16_t>(port)};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli("a seeded UDP relay with latency, jitter, loss, duplication and reordering",
               "link_relay");
  std::string upstream, port_file;
  fixstep::net::LinkSettings link;
  std::uint16_t port = 0;
  double seconds = 60.0;
  cli.add_option("--upstream", upstream, "where the peers' datagrams go (HOST:PORT)")->required();
  cli.add_option("--latency-ms", link.latency_ms)->check(CLI::Range(0.0, 10000.0));
  cli.add_option("--jitter-ms", link.jitter_ms)->check(CLI::Range(0.0, 10000.0));
  cli.add_option("--loss", link.loss)->check(CLI::Range(0.0, 1.0));
  cli.add_option("--duplicate", link.duplicate)->check(CLI::Range(0.0, 1.0));
  cli.add_option("--reorder", link.reorder)->check(CLI::Range(0.0, 1.0));
  cli.add_option("--lossless-ms", link.lossless_ms, "nothing lost for this long at first")
      ->check(CLI::Range(0.0, 3600000.0));
  cli.add_option("--seed", link.seed);
  cli.add_option("--port", port, "the relay's port (0: any)");
  cli.add_option("--port-file", port_file, "write the relay's port into FILE");
  cli.add_option("--seconds", seconds, "stop after this long")->check(CLI::Range(0.1, 3600.0));
  fixstep::net::Address up;
  try {
    cli.parse(argc, argv);
    up = host_port(upstream);
  } catch (const CLI::ParseError& e) {
    return cli.exit(e);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "link_relay: --upstream %s: %s\n", upstream.c_str(), e.what());
    return 2;
  }
  try {
    fixstep::net::LinkConditioner relay(up, link, fixstep::net::Address{"127.0.0.1", port});
    std::printf("link_relay: 127.0.0.1:%u -> %s:%u\n", static_cast<unsigned>(relay.port()),
                up.host.c_str(), static_cast<unsigned>(up.port));
    std::fflush(stdout);
    if (!port_file.empty()) std::ofstream(port_file) << relay.port() << "\n";
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (!stop && std::chrono::steady_clock::now() < end) {
      relay.pump();
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    const fixstep::net::LinkStats s = relay.stats();
    std::printf("link_relay: received=%llu dropped=%llu duplicated=%llu delivered=%llu\n",
                static_cast<unsigned long long>(s.received),
                static_cast<unsigned long long>(s.dropped),
                static_cast<unsigned long long>(s.duplicated),
                static_cast<unsigned long long>(s.delivered));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "link_relay: error: %s\n", e.what());
    return 1;
  }
}
