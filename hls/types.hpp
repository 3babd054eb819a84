// The one header the kernels include for their arithmetic types.
#pragma once
#include "hls/fixed_point.hpp"
