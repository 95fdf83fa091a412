#pragma once
// A core header that reaches up into the simulation: what the rule forbids.
#include "step.h"
