// `voxcast flythrough`: the virtual-endoscopy evaluation of the VIZARD II
// paper (2001, §2.3 and §3: frame rates "for flythroughs, as presented in this
// paper"), reproduced on the cycle model. The camera follows the scene's
// camera.path; every frame is rendered by the rtl engine, which gives the
// pixels (bit-exact with hls) and the card's cycles, so the table says what
// frame rate the card would sustain along the flight.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"
#include "rtl_model/pci/pci_bus.hpp"
#include "rtl_model/pci/pci_dma.hpp"
#include "rtl_model/pipeline/stats.hpp"

namespace voxcast::cosim {

struct FlythroughOptions {
  std::string out_dir;
  int frames = 0;              // 0: the scene's render.frames if > 1, else 24
  int animation_fps = 10;      // playback rate of the GIF (not the modelled rate)
  // Temporal stability against the truth (cosim/engines/truth.hpp) at this
  // oversampling, rendered per frame with the float reference; 0: no truth
  // (the figure is then the rendered change alone).
  double truth_oversampling = 16.0;
};

// Temporal stability of frame f against frame f - 1 (issue 19 part 2), over
// every pixel channel in output LSBs: the rendered frame-to-frame change
// d = I_f - I_{f-1}, and the flicker |d - t| against the truth's change t =
// T_f - T_{f-1} (the truth in LSBs, unrounded): the change the truth does
// not have. Frame 0 has none (zeros).
struct TemporalStability {
  double change_max = 0.0, change_mean = 0.0;
  double flicker_max = 0.0, flicker_mean = 0.0;  // 0 without a truth
};

struct FlythroughFrame {
  int index = 0;
  ref::CameraPose pose;
  rtl::pipeline::RtlStats stats;  // the card's timing of this frame
  std::string image;              // the frame's PNG
  TemporalStability stability;    // against the previous frame
};

struct FlythroughResult {
  std::vector<FlythroughFrame> frames;
  rtl::pci::HostTransfers host;  // volume upload once, tables, readback per frame
  // The readback on the clocked PCI model (pci/pci_dma.hpp: the frame
  // buffer's words cross to the 33 MHz domain through an asynchronous FIFO)
  // and, per frame, its overlap with the next frame's rendering (double-
  // buffered frame buffer): readback time, stall, hidden or not.
  rtl::pci::PciStats clocked_readback;
  std::vector<rtl::pci::FrameReadback> readback;
  // The flight's temporal stability: the largest of the frames' maxima and the
  // mean of their means (frames 1 .. n-1).
  TemporalStability stability;
  bool has_truth = false;
  std::string animation, csv, json;
  double wall_seconds = 0.0;     // host time to simulate every frame
};

// Renders every frame along camera.path with the rtl engine and writes
// DIR/frame_NNNN.png, DIR/flythrough.gif, DIR/frames.csv and DIR/frames.json.
// Throws voxcast::Error if the scene has fewer than two keyframes, for a
// profile the rtl engine is not compiled for, or if DIR cannot be written.
// Frames are simulated in parallel (each frame single-threaded); the results
// do not depend on the thread count.
FlythroughResult run_flythrough(const ref::Scene& scene, const FlythroughOptions& options);

void print_flythrough(std::ostream& os, const ref::Scene& scene, const FlythroughResult& r);

}  // namespace voxcast::cosim
