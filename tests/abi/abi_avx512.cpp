// SPDX-License-Identifier: BSD-3-Clause
#include "abi/abi_run.hpp"

AbiReport run_with_avx512() { return run_here(); }
