#include "rtl_model/virim/config.hpp"

#include <cmath>
#include <ostream>
#include <string>

#include "refmodel/error.hpp"

namespace voxcast::rtl::virim {
namespace {

void check_int(const char* name, int v, int lo, int hi) {
  if (v < lo || v > hi)
    throw Error(std::string("virim rtl: ") + name + " = " + std::to_string(v) + " is outside [" +
                std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

void check_mhz(const char* name, double v) {
  if (!std::isfinite(v) || v < 1.0 || v > 1000.0)
    throw Error(std::string("virim rtl: ") + name + " = " + std::to_string(v) +
                " MHz is outside [1, 1000]");
}

}  // namespace

void validate(const VirimRtlConfig& c) {
  check_int("modules", c.modules, 1, 64);
  check_int("dsps_per_module", c.dsps_per_module, 1, 64);
  check_mhz("rotator_mhz", c.rotator_mhz);
  check_mhz("dsp_mhz", c.dsp_mhz);
  check_mhz("bus_mhz", c.bus_mhz);
  check_int("bank_cycle_clocks", c.bank_cycle_clocks, 1, 64);
  check_int("dsp_cycles_per_voxel", c.dsp_cycles_per_voxel, 1, 100000);
  check_int("dsp_fifo_words", c.dsp_fifo_words, 1, 1 << 24);
  check_int("bus_fifo_words", c.bus_fifo_words, 1, 1 << 24);
  check_int("interpolation_latency", c.interpolation_latency, 0, 1000);
  check_int("gradient_latency", c.gradient_latency, 0, 1000);
}

VirimRtlConfig virim_rtl_config(const ref::HeidelbergDesc& h) {
  VirimRtlConfig c;
  c.modules = h.modules;
  c.rotator_mhz = h.rotator_mhz;
  c.dsp_mhz = h.dsp_mhz;
  c.bus_mhz = h.bus_mhz;
  validate(c);
  return c;
}

std::ostream& operator<<(std::ostream& os, const VirimRtlConfig& c) {
  return os << c.modules << " module(s) x (1 rotator + " << c.dsps_per_module << " DSPs); rotator "
            << c.rotator_mhz << " MHz, bus " << c.bus_mhz << " MHz, DSP " << c.dsp_mhz
            << " MHz; bank cycle " << c.bank_cycle_clocks << " clocks, ping-pong "
            << (c.ping_pong ? "on" : "off") << ", repeat suppression "
            << (c.suppress_repeats ? "on" : "off") << ", out-of-range reads "
            << (c.zero_out_of_range ? "free" : "cost a bank cycle") << "; DSP " << c.dsp_cycles_per_voxel
            << " cycles/voxel, FIFO " << c.dsp_fifo_words << " words; bus buffer "
            << c.bus_fifo_words << " words";
}

}  // namespace voxcast::rtl::virim
