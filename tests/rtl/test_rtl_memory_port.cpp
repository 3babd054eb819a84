// The event-driven memory ports against the reference Controller ticked
// every cycle: the in-order port (rtl_model/pipeline/fast_in_order_port.hpp),
// the look-ahead port (fast_lookahead_port.hpp) and, for every policy, the reference port ticked
// only at the controller's next events (reference_port.hpp, CommandScheduler::wake). Random request
// streams with bank and row locality, pushed at random cycles and with
// random consumer back-pressure, must give the same completions (request,
// row outcome, first command, column command, data window) in the same
// cycles, and the same statistics.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/pipeline/fast_in_order_port.hpp"
#include "rtl_model/pipeline/fast_lookahead_port.hpp"
#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/geometry.hpp"
#include "rtl_model/sdram/observer.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::pipeline::MemoryModel;
using rtl::pipeline::MemoryPort;
using rtl::sdram::Completion;

struct Served {
  std::vector<Completion> done;
  std::vector<rtl::sim::Cycle> at;
};

// bank_change: the share of requests that move to another bank (with a new
// row at times), which is what the reordering policies act on.
Served drive(MemoryPort& port, std::uint32_t seed, rtl::sim::Cycle cycles, double pop_rate,
             double bank_change = 0.12, std::uint32_t banks = 4) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Served run;
  std::uint64_t id = 0;
  std::uint32_t bank = 0, row = 0, column = 0;
  for (rtl::sim::Cycle now = 0; now < cycles; ++now) {
    // Requests: mostly the next column, sometimes a new row or bank.
    if (u(rng) < 0.7 && port.ready()) {
      const double r = u(rng);
      if (r < bank_change * 2 / 3) row = static_cast<std::uint32_t>(rng() % 4096);
      if (r < bank_change) bank = static_cast<std::uint32_t>(rng() % banks);
      column = (column + 1) % 512;
      port.push(rtl::sdram::Request{id++, rtl::sdram::RequestKind::kRead, {bank, row, column}, now});
    }
    port.tick(now);
    if (port.completions().valid() && u(rng) < pop_rate) {
      run.done.push_back(port.completions().pop());
      run.at.push_back(now);
      port.popped(now);
    }
  }
  return run;
}

// Every command a port puts on the DIMM's bus, in order.
struct CommandLog final : rtl::sdram::CommandObserver {
  struct Entry {
    rtl::sdram::Command cmd;
    rtl::sdram::Address a;
    rtl::sim::Cycle at;
    bool operator==(const Entry&) const = default;
  };
  std::vector<Entry> log;
  void on_command(rtl::sdram::Command cmd, const rtl::sdram::Address& a,
                  rtl::sim::Cycle now) override {
    log.push_back({cmd, a, now});
  }
};

// The same commands (kind, address, cycle) in the same order.
void compare_commands(const CommandLog& ref, const CommandLog& fast) {
  ASSERT_EQ(ref.log.size(), fast.log.size());
  for (std::size_t i = 0; i < ref.log.size(); ++i) {
    const auto& x = ref.log[i];
    ASSERT_EQ(x, fast.log[i]) << "command " << i << ": reference " << x.cmd << " bank " << x.a.bank
                              << " row " << x.a.row << " at cycle " << x.at;
  }
}

// `fast` against `ref` after the same stream.
void compare_runs(const MemoryPort& ref, const MemoryPort& fast, const Served& a, const Served& b);

void compare(const rtl::sdram::DimmConfig& dimm, const rtl::sdram::ControllerConfig& cc,
             std::uint32_t seed, double pop_rate) {
  const rtl::sim::Cycle cycles = 8000;  // at least three refresh intervals
  auto ref = rtl::pipeline::make_memory_port(MemoryModel::kReference, "in-order", "eager", dimm, cc, false);
  auto fast = rtl::pipeline::make_memory_port(MemoryModel::kAuto, "in-order", "eager", dimm, cc, true);
  ASSERT_NE(dynamic_cast<rtl::pipeline::FastInOrderPort*>(fast.get()), nullptr);
  CommandLog ref_log, fast_log;
  ref->set_observer(&ref_log);
  fast->set_observer(&fast_log);
  const Served a = drive(*ref, seed, cycles, pop_rate);
  const Served b = drive(*fast, seed, cycles, pop_rate);
  compare_commands(ref_log, fast_log);
  compare_runs(*ref, *fast, a, b);
}

void compare_runs(const MemoryPort& ref, const MemoryPort& fast, const Served& a, const Served& b) {
  ASSERT_EQ(a.done.size(), b.done.size());
  ASSERT_GT(a.done.size(), 400u);
  for (std::size_t i = 0; i < a.done.size(); ++i) {
    SCOPED_TRACE(::testing::Message() << "completion " << i << ": reference " << a.done[i]);
    ASSERT_EQ(a.at[i], b.at[i]);
    ASSERT_EQ(a.done[i].request.id, b.done[i].request.id);
    ASSERT_EQ(a.done[i].request.arrival, b.done[i].request.arrival);
    ASSERT_EQ(a.done[i].outcome, b.done[i].outcome);
    ASSERT_EQ(a.done[i].first_command, b.done[i].first_command);
    ASSERT_EQ(a.done[i].column_command, b.done[i].column_command);
    ASSERT_EQ(a.done[i].data.first, b.done[i].data.first);
    ASSERT_EQ(a.done[i].data.last, b.done[i].data.last);
  }
  const auto& x = ref.controller_stats();
  const auto& y = fast.controller_stats();
  EXPECT_EQ(x.requests, y.requests);
  EXPECT_EQ(x.row_hits, y.row_hits);
  EXPECT_EQ(x.row_misses, y.row_misses);
  EXPECT_EQ(x.row_conflicts, y.row_conflicts);
  EXPECT_EQ(x.command_cycles, y.command_cycles);
  EXPECT_EQ(x.refresh_cycles, y.refresh_cycles);
  EXPECT_EQ(x.latency_sum, y.latency_sum);
  EXPECT_EQ(x.latency_max, y.latency_max);
  EXPECT_EQ(x.reads, y.reads);
  EXPECT_EQ(x.completed, y.completed);
  EXPECT_EQ(x.bytes, y.bytes);
  EXPECT_EQ(x.auto_precharges, y.auto_precharges);
  const auto& p = ref.dimm_stats();
  const auto& q = fast.dimm_stats();
  EXPECT_EQ(p.commands, q.commands);
  EXPECT_EQ(p.refreshes, q.refreshes);
  EXPECT_GE(q.refreshes, 3u);
  EXPECT_EQ(p.precharge_alls, q.precharge_alls);
  EXPECT_EQ(p.data_bus_busy_cycles, q.data_bus_busy_cycles);
  EXPECT_EQ(p.refresh_busy_cycles, q.refresh_busy_cycles);
  for (std::size_t k = 0; k < p.banks.size(); ++k) {
    EXPECT_EQ(p.banks[k].activates, q.banks[k].activates);
    EXPECT_EQ(p.banks[k].precharges, q.banks[k].precharges);
    EXPECT_EQ(p.banks[k].auto_precharges, q.banks[k].auto_precharges);
    EXPECT_EQ(p.banks[k].reads, q.banks[k].reads);
    EXPECT_EQ(p.banks[k].open_cycles, q.banks[k].open_cycles);
  }
  EXPECT_EQ(ref.pending(), fast.pending());
  EXPECT_EQ(ref.in_flight(), fast.in_flight());
}

TEST(FastInOrderPort, EqualsTheReferenceController) {
  const auto grades = {rtl::sdram::presets::pc100_cl2(), rtl::sdram::presets::pc100_cl3()};
  std::uint32_t seed = 1;
  for (const auto& grade : grades)
    for (int bl : {1, 2, 4, 8})
      for (std::size_t queue : {std::size_t{1}, std::size_t{8}})
        for (std::size_t ret : {std::size_t{1}, std::size_t{8}})
          for (double pop : {1.0, 0.3}) {
            SCOPED_TRACE(::testing::Message() << grade.name << " BL" << bl << " queue " << queue
                                              << " return " << ret << " pop " << pop);
            rtl::sdram::DimmConfig d;
            d.timing = grade;
            d.burst_length = bl;
            compare(d, rtl::sdram::ControllerConfig{queue, ret}, seed++, pop);
          }
  // PC133 at its own clock.
  rtl::sdram::DimmConfig d133;
  d133.timing = rtl::sdram::presets::pc133_cl3();
  d133.clock = rtl::sim::clocks::pc133();
  compare(d133, rtl::sdram::ControllerConfig{}, 99, 1.0);
}

// The look-ahead port (fast_lookahead_port.hpp) against the reference
// Controller with the look-ahead scheduler ticked every cycle: the same
// commands (kind, address, cycle), completions and statistics, open page and
// auto precharge, windows of 1 (in-order rows), 2 and 8, streams that stay
// in a bank and streams that change banks often (what the look-ahead acts on).
TEST(FastLookAheadPort, EqualsTheReferenceController) {
  std::uint32_t seed = 900;
  std::uint64_t rda = 0;
  for (const auto& grade : {rtl::sdram::presets::pc100_cl2(), rtl::sdram::presets::pc100_cl3()})
    for (int bl : {1, 4})
      for (std::size_t ret : {std::size_t{1}, std::size_t{8}})
        for (int window : {1, 2, 8})
          for (bool auto_precharge : {false, true})
            for (double pop : {1.0, 0.3})
              for (double bank_change : {0.12, 0.5}) {
                SCOPED_TRACE(::testing::Message()
                             << grade.name << " BL" << bl << " return " << ret << " window "
                             << window << (auto_precharge ? " auto precharge" : " open page")
                             << " pop " << pop << " bank change " << bank_change);
                rtl::sdram::DimmConfig d;
                d.timing = grade;
                d.burst_length = bl;
                rtl::sdram::ControllerConfig cc{8, ret};
                cc.auto_precharge = auto_precharge;
                const rtl::sdram::SchedulerParams params{.reorder_window = window};
                auto ref = rtl::pipeline::make_memory_port(MemoryModel::kReference, "lookahead",
                                                           "eager", d, cc, false, params);
                auto fast = rtl::pipeline::make_memory_port(MemoryModel::kAuto, "lookahead",
                                                            "eager", d, cc, true, params);
                ASSERT_NE(dynamic_cast<rtl::pipeline::FastLookAheadPort*>(fast.get()), nullptr);
                CommandLog ref_log, fast_log;
                ref->set_observer(&ref_log);
                fast->set_observer(&fast_log);
                const Served a = drive(*ref, seed, 8000, pop, bank_change);
                const Served b = drive(*fast, seed, 8000, pop, bank_change);
                ++seed;
                compare_commands(ref_log, fast_log);
                compare_runs(*ref, *fast, a, b);
                rda += fast->controller_stats().auto_precharges;
              }
  // The streams exercise the auto precharge (EventDrivenPort.ThePoliciesDiffer
  // shows that they make the look-ahead schedule differ from the in-order one).
  EXPECT_GT(rda, 1000u);
}

// Both event-driven ports on a DDR4 module (16 banks in 4 bank groups, BL8
// in 4 clocks): the same commands, completions and statistics as the
// reference, with streams over every bank, so that the bank-group timing
// (tCCD_L and tRRD_L within a group, tCCD_S and tRRD_S across; tFAW) decides
// cycles. The ports take the group of a bank and the burst's clocks from the
// module, as the Dimm does.
TEST(FastPorts, Ddr4BankGroupsEqualTheReference) {
  rtl::sdram::DimmConfig d;
  d.geometry = rtl::sdram::geometries::mta18asf2g72pz();
  d.timing = rtl::sdram::presets::ddr4_2400_cl17();
  d.clock = rtl::sim::clocks::ddr4_2400();
  d.burst_length = 8;
  ASSERT_EQ(d.geometry.bank_groups, 4u);
  std::uint32_t seed = 1200;
  for (const char* policy : {"in-order", "lookahead"})
    for (bool auto_precharge : {false, true})
      for (double bank_change : {0.12, 0.5}) {
        if (std::string(policy) == "in-order" && auto_precharge) continue;  // (the reference's)
        SCOPED_TRACE(::testing::Message() << policy << (auto_precharge ? " auto precharge" : "")
                                          << " bank change " << bank_change);
        rtl::sdram::ControllerConfig cc{8, 8};
        cc.auto_precharge = auto_precharge;
        const rtl::sdram::SchedulerParams params{.reorder_window = 8};
        auto ref = rtl::pipeline::make_memory_port(MemoryModel::kReference, policy, "eager", d, cc,
                                                   false, params);
        auto fast = rtl::pipeline::make_memory_port(MemoryModel::kAuto, policy, "eager", d, cc,
                                                    true, params);
        ASSERT_NE(dynamic_cast<rtl::pipeline::EventDrivenPort*>(fast.get()), nullptr);
        CommandLog ref_log, fast_log;
        ref->set_observer(&ref_log);
        fast->set_observer(&fast_log);
        // Three refresh intervals of DDR4-2400 (tREFI 7.8 us: 9,360 clocks).
        const Served a = drive(*ref, seed, 30000, 1.0, bank_change, d.geometry.banks);
        const Served b = drive(*fast, seed, 30000, 1.0, bank_change, d.geometry.banks);
        ++seed;
        compare_commands(ref_log, fast_log);
        compare_runs(*ref, *fast, a, b);
      }
}

// A request the event-driven ports cannot serve is an error that names the
// port and the cycle, not a silently wrong schedule.
TEST(FastPorts, RejectRequestsTheyCannotServe) {
  const rtl::sdram::DimmConfig d;  // PC100, 4 banks
  const rtl::sdram::ControllerConfig cc{2, 8};
  const rtl::sdram::Address inside{1, 2, 3};
  const auto expect_error = [](auto&& f, const std::string& what) {
    try {
      f();
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("controller at cycle 5"), std::string::npos) << e.what();
    }
  };
  for (const char* policy : {"in-order", "lookahead"}) {
    SCOPED_TRACE(policy);
    auto port = rtl::pipeline::make_memory_port(MemoryModel::kAuto, policy, "eager", d, cc, true);
    ASSERT_NE(dynamic_cast<rtl::pipeline::EventDrivenPort*>(port.get()), nullptr);
    using rtl::sdram::Request;
    using rtl::sdram::RequestKind;
    expect_error(
        [&] {
          port->push(Request{0, RequestKind::kRead, {4, 0, 0}, 5});
        },
        "request outside the DIMM");
    expect_error(
        [&] {
          port->push(Request{0, RequestKind::kRead, {0, d.geometry.rows, 0}, 5});
        },
        "request outside the DIMM");
    expect_error(
        [&] {
          port->push(Request{0, RequestKind::kRead, {0, 0, d.geometry.columns}, 5});
        },
        "request outside the DIMM");
    expect_error(
        [&] {
          port->push(Request{0, RequestKind::kWrite, inside, 5});
        },
        "a write request");
    // The queue holds two; the third push is refused, and nothing was taken.
    port->push(Request{1, RequestKind::kRead, inside, 5});
    port->push(Request{2, RequestKind::kRead, inside, 5});
    EXPECT_FALSE(port->ready());
    expect_error(
        [&] {
          port->push(Request{3, RequestKind::kRead, inside, 5});
        },
        "request queue is full");
    EXPECT_EQ(port->pending(), 2u);
    EXPECT_EQ(port->controller_stats().requests, 2u);
  }
}

// Every policy, event-driven (the reference port ticked at the controller's
// next events) against the same policy ticked every cycle. FR-FCFS with a
// starvation limit of 3 so that starved phases occur; a window of 1 and 8.
TEST(EventDrivenPort, EveryPolicyEqualsTheControllerTickedEveryCycle) {
  std::uint32_t seed = 500;
  for (const char* policy : {"in-order", "fr-fcfs", "lookahead"})
    for (const auto& grade : {rtl::sdram::presets::pc100_cl2(), rtl::sdram::presets::pc100_cl3()})
      for (int bl : {1, 4})
        for (std::size_t ret : {std::size_t{1}, std::size_t{8}})
          for (int window : {1, 8})
            for (double pop : {1.0, 0.3}) {
              SCOPED_TRACE(::testing::Message() << policy << " " << grade.name << " BL" << bl
                                                << " return " << ret << " window " << window
                                                << " pop " << pop);
              rtl::sdram::DimmConfig d;
              d.timing = grade;
              d.burst_length = bl;
              const rtl::sdram::ControllerConfig cc{8, ret};
              const rtl::sdram::SchedulerParams params{.reorder_window = window,
                                                       .starvation_limit = 3};
              auto ref = rtl::pipeline::make_memory_port(MemoryModel::kReference, policy, "eager",
                                                         d, cc, false, params);
              auto fast = rtl::pipeline::make_memory_port(MemoryModel::kReference, policy, "eager",
                                                          d, cc, true, params);
              const Served a = drive(*ref, seed, 8000, pop, 0.5);
              const Served b = drive(*fast, seed, 8000, pop, 0.5);
              ++seed;
              compare_runs(*ref, *fast, a, b);
              // The event-driven port skipped ticks: it is not the reference ticked every cycle.
              EXPECT_LT(fast->controller_stats().cycles, ref->controller_stats().cycles);
            }
}

// The policies reorder: on these streams FR-FCFS and look-ahead complete
// requests out of arrival order or earlier than in-order does, so the
// comparison above is not between three copies of the in-order schedule.
TEST(EventDrivenPort, ThePoliciesDiffer) {
  rtl::sdram::DimmConfig d;
  const rtl::sdram::ControllerConfig cc{8, 8};
  const rtl::sdram::SchedulerParams params{.reorder_window = 8, .starvation_limit = 64};
  std::vector<rtl::sim::Cycle> last;
  for (const char* policy : {"in-order", "fr-fcfs", "lookahead"}) {
    auto port = rtl::pipeline::make_memory_port(MemoryModel::kReference, policy, "eager", d, cc,
                                                true, params);
    const Served r = drive(*port, 7, 8000, 1.0, 0.5);
    std::vector<rtl::sim::Cycle> cols;
    for (const Completion& c : r.done) cols.push_back(c.column_command);
    if (!last.empty()) {
      EXPECT_NE(cols, last) << policy;
    }
    last = cols;
  }
}

}  // namespace
}  // namespace voxcast::test
