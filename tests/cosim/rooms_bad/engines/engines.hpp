// A fixture for the test cosim.rooms_catches: a legal include.
#pragma once
#include "cosim/reports/files.hpp"
