// swa_netem: packet loss and delay for the `loss` tests, where the kernel has no netem qdisc. Takes the packets an
// nftables rule sends to NFQUEUE queue N (in the network namespace it runs in), drops each with probability --loss and
// holds the others for --delay-ms ± --jitter-ms before letting them through (impairment.h). Runs until SIGINT or
// SIGTERM, then lets every held packet through and prints one line of counts on stdout.
//
//   nft add table inet swa_loss
//   nft add chain inet swa_loss out '{ type filter hook output priority 0; }'
//   nft add rule inet swa_loss out meta l4proto udp queue num 7
//   swa_netem --queue 7 --loss 0.1 --delay-ms 20 --jitter-ms 10 --seed 1
//
// Needs CAP_NET_ADMIN (root in the namespace). A packet the queue cannot take (full, or this program gone) is dropped
// by the kernel (no fail-open): the rule must be removed before this program stops for good.

#include <arpa/inet.h>
#include <linux/netfilter.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern "C" {
#include <libnetfilter_queue/libnetfilter_queue.h>
}

#include "impairment.h"

namespace {

std::atomic<bool> g_stop{false};
extern "C" void onSignal(int) { g_stop = true; }

struct Counts {
  unsigned long long seen = 0, dropped = 0, delayed = 0, verdict_errors = 0;
};

struct State {
  nfq_q_handle* queue = nullptr;
  swa::netem::Impairment* impairment = nullptr;
  swa::netem::ReleaseQueue held;
  Counts counts;
};

int onPacket(nfq_q_handle* qh, nfgenmsg*, nfq_data* nfa, void* data) {
  auto* s = static_cast<State*>(data);
  const nfqnl_msg_packet_hdr* ph = nfq_get_msg_packet_hdr(nfa);
  if (ph == nullptr) return 0;
  const std::uint32_t id = ntohl(ph->packet_id);
  ++s->counts.seen;
  const auto delay = s->impairment->decide();
  if (!delay) {
    ++s->counts.dropped;
    if (nfq_set_verdict(qh, id, NF_DROP, 0, nullptr) < 0) ++s->counts.verdict_errors;
  } else if (delay->count() == 0) {
    if (nfq_set_verdict(qh, id, NF_ACCEPT, 0, nullptr) < 0) ++s->counts.verdict_errors;
  } else {
    ++s->counts.delayed;
    s->held.hold(swa::netem::Clock::now() + *delay, id);
  }
  return 0;
}

void usage(FILE* to) {
  std::fputs(
      "Usage: swa_netem --queue N [--loss P] [--delay-ms D] [--jitter-ms J] [--seed S]\n"
      "  Drops packets of NFQUEUE queue N with probability P (0 <= P < 1) and holds\n"
      "  the others for D +- J ms (uniform; 0 <= J <= D). Seeded (default 1). Until\n"
      "  SIGINT/SIGTERM; then prints on stdout\n"
      "  'swa_netem: seen X dropped Y delayed Z verdict_errors E'. Needs CAP_NET_ADMIN.\n",
      to);
}

bool parseDouble(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  int queue_num = -1;
  swa::netem::ImpairmentConfig config;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") {
      usage(stdout);
      return 0;
    }
    double v = 0.0;
    if (i + 1 >= argc || !parseDouble(argv[i + 1], v)) {
      std::fprintf(stderr, "swa_netem: %s needs a number\n", a.c_str());
      usage(stderr);
      return 2;
    }
    ++i;
    if (a == "--queue" && v >= 0 && v <= 65535) {
      queue_num = static_cast<int>(v);
    } else if (a == "--loss") {
      config.loss = v;
    } else if (a == "--delay-ms") {
      config.delay = std::chrono::microseconds(static_cast<std::int64_t>(v * 1000.0));
    } else if (a == "--jitter-ms") {
      config.jitter = std::chrono::microseconds(static_cast<std::int64_t>(v * 1000.0));
    } else if (a == "--seed" && v >= 0) {
      config.seed = static_cast<std::uint64_t>(v);
    } else {
      std::fprintf(stderr, "swa_netem: bad option %s %s\n", a.c_str(), argv[i]);
      usage(stderr);
      return 2;
    }
  }
  if (queue_num < 0) {
    usage(stderr);
    return 2;
  }
  State state;
  try {
    static swa::netem::Impairment impairment(config);
    state.impairment = &impairment;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "swa_netem: %s\n", e.what());
    return 2;
  }

  nfq_handle* h = nfq_open();
  if (h == nullptr) {
    std::fprintf(stderr, "swa_netem: nfq_open failed: %s (needs CAP_NET_ADMIN)\n", std::strerror(errno));
    return 1;
  }
  state.queue = nfq_create_queue(h, static_cast<std::uint16_t>(queue_num), &onPacket, &state);
  if (state.queue == nullptr) {
    std::fprintf(stderr, "swa_netem: cannot bind NFQUEUE %d: %s\n", queue_num, std::strerror(errno));
    nfq_close(h);
    return 1;
  }
  // Only the packet id is needed for a verdict: no payload copied to user space.
  if (nfq_set_mode(state.queue, NFQNL_COPY_META, 0) < 0 || nfq_set_queue_maxlen(state.queue, 65536) < 0) {
    std::fprintf(stderr, "swa_netem: cannot configure queue %d\n", queue_num);
    nfq_destroy_queue(state.queue);
    nfq_close(h);
    return 1;
  }
  nfnl_rcvbufsiz(nfq_nfnlh(h), 16 * 1024 * 1024);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  std::fprintf(stderr, "swa_netem: queue %d, loss %.3f, delay %.1f +- %.1f ms, seed %llu\n", queue_num, config.loss,
               static_cast<double>(config.delay.count()) / 1000.0, static_cast<double>(config.jitter.count()) / 1000.0,
               static_cast<unsigned long long>(config.seed));

  const int fd = nfq_fd(h);
  std::vector<char> buf(256 * 1024);
  const auto release = [&](std::uint32_t id) {
    if (nfq_set_verdict(state.queue, id, NF_ACCEPT, 0, nullptr) < 0) ++state.counts.verdict_errors;
  };
  while (!g_stop) {
    int timeout_ms = 100;
    if (const auto next = state.held.next()) {
      const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(*next - swa::netem::Clock::now());
      timeout_ms = static_cast<int>(std::max<std::int64_t>(0, std::min<std::int64_t>(wait.count(), 100)));
    }
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) > 0 && (p.revents & POLLIN) != 0) {
      // Drain what is there without blocking, so delays are not stretched by a burst.
      while (true) {
        const ssize_t n = ::recv(fd, buf.data(), buf.size(), MSG_DONTWAIT);
        if (n <= 0) break;
        nfq_handle_packet(h, buf.data(), static_cast<int>(n));
      }
    }
    state.held.releaseDue(swa::netem::Clock::now(), release);
  }
  state.held.releaseDue(swa::netem::Clock::time_point::max(), release);
  std::printf("swa_netem: seen %llu dropped %llu delayed %llu verdict_errors %llu\n", state.counts.seen,
              state.counts.dropped, state.counts.delayed, state.counts.verdict_errors);
  std::fflush(stdout);
  nfq_destroy_queue(state.queue);
  nfq_close(h);
  return 0;
}
