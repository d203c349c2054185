// uniparam/core/error.hpp -- the exception hierarchy of the whole engine: the
// public uniparam/error.hpp.
#pragma once

#include "uniparam/error.hpp"
