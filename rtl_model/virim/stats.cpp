#include "rtl_model/virim/stats.hpp"

#include <ostream>

namespace voxcast::rtl::virim {

double VirimRtlStats::rotation_rate() const {
  if (rotating_cycles == 0) return 0.0;
  // rotating_cycles sums the modules': per module on average voxels/modules
  // take rotating_cycles/modules clocks.
  return static_cast<double>(voxels) * rotator_mhz * 1e6 * modules /
         static_cast<double>(rotating_cycles);
}

double VirimRtlStats::mean_access_ns() const {
  return unit_reads ? static_cast<double>(access_cycles) / static_cast<double>(unit_reads) * 1e3 /
                          rotator_mhz
                    : 0.0;
}

double VirimRtlStats::dsp_utilisation() const {
  const double dsp_cycles = frame_ns * 1e-3 * dsp_mhz * dsps;
  return dsp_cycles > 0 ? static_cast<double>(dsp_busy_cycles) / dsp_cycles : 0.0;
}

std::ostream& operator<<(std::ostream& os, const VirimRtlStats& s) {
  return os << s.cycles << " rotator cycles, " << s.frame_ns * 1e-6 << " ms/frame (" << s.fps()
            << " fps); rotation " << s.rotation_rate() * 1e-6 << " M voxels/s (peak "
            << s.peak_rotation_rate() * 1e-6 << "); memory: " << s.ram_reads << " RAM reads, "
            << s.suppressed << " suppressed, " << s.out_of_range << " out of range of "
            << s.unit_reads << ", mean access " << s.mean_access_ns() << " ns; DSP utilisation "
            << s.dsp_utilisation() * 100.0 << "%";
}

}  // namespace voxcast::rtl::virim
