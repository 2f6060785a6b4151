// A lower folder including a higher one: check_layers.cmake must fail on this tree.
#pragma once
#include "pipeline/high.h"
