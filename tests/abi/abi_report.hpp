// SPDX-License-Identifier: BSD-3-Clause
// What each of the translation units of mpsfsi_abi_tests reports. No mpsfsi type crosses
// between them: each is compiled for another instruction set.
#pragma once

#include <string>
#include <vector>

struct AbiReport {
  int lanes = 0;            // CorrectedTotalLagrangian<2>::lanes in that unit
  std::string solver_type;  // typeid(mpsfsi::ElasticSolver<2>).name(): the symbol it links to
  std::vector<double> positions;  // x and y of every particle after the run
};

AbiReport run_with_avx512();  // abi_avx512.cpp, built with -march=x86-64-v4 (where the compiler has it)
AbiReport run_with_avx();     // abi_avx.cpp, built with -mavx2 -mfma
AbiReport run_with_sse2();    // abi_sse2.cpp, built with -mno-avx
