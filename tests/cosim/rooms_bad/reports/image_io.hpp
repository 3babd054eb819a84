// A fixture for the test cosim.rooms_catches: a report that reaches up into
// the engines, against the rooms' order.
#pragma once
#include "cosim/engines/engines.hpp"
