// A listener to the commands a DIMM accepts (the VCD trace,
// rtl_model/trace/). Dimm::issue and the event-driven in-order port call it
// after every accepted command when one is set; with none set the cost is
// one null-pointer test per command.
#pragma once

#include "rtl_model/sdram/command.hpp"

namespace voxcast::rtl::sdram {

class CommandObserver {
 public:
  virtual ~CommandObserver() = default;
  // PREA and REF carry a zero address.
  virtual void on_command(Command cmd, const Address& a, Cycle now) = 0;
};

}  // namespace voxcast::rtl::sdram
