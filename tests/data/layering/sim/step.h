#pragma once
// A simulation header.
#include "clock.h"
