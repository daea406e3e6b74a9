#pragma once
#include "spectral/b.h"
