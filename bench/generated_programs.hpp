#pragma once
// The generated 1M-block programs the NC benchmarks share (nc_decode_bench, block_search_bench):
// straight moves (MTC200), expressions and loops with subprogram calls (ISG).

#include <cstdio>
#include <string>

namespace vmt::bench {

constexpr int kBlocks = 1000000;

inline std::string StraightMtc200() {
  std::string s;
  s.reserve(kBlocks * 32);
  char line[96];
  for (int i = 0; i < kBlocks; ++i) {
    std::snprintf(line, sizeof line, "N%04d G01 X%.3f Z%.3f F%d\n", i % 10000,
                  10 + (i % 977) * 0.125, -(i % 613) * 0.25, 500 + i % 7 * 100);
    s += line;
  }
  return s;
}

inline std::string ExpressionsIsg() {
  std::string s = "%expr\n";
  s.reserve(kBlocks * 48);
  char line[128];
  for (int i = 0; i < kBlocks; ++i) {
    std::snprintf(line, sizeof line, "N%d P%d = [P%d + %d.5] * 2 / [1 + P%d] X[P%d * 0.5 - %d]\n",
                  i, i % 50 + 1, (i + 7) % 50 + 1, i % 13, (i + 3) % 50 + 1, i % 50 + 1, i % 31);
    s += line;
  }
  return s;
}

inline std::string LoopsIsg() {
  // Loop and subprogram structure repeated: $FOR, $IF, $WHILE and L calls between moves.
  std::string s = "%loops\n";
  s.reserve(kBlocks * 24);
  for (int i = 0; i < kBlocks / 10; ++i) {
    s += "$FOR P1 = 1, 10, 1\n";
    s += "$IF P1 == 5\n";
    s += "L sub_a\n";
    s += "$ELSE\n";
    s += "G01 X[P1] Y[P1 * 2] F1000\n";
    s += "$ENDIF\n";
    s += "$WHILE P2 < 3\n";
    s += "P2 = P2 + 1\n";
    s += "$ENDWHILE\n";
    s += "$ENDFOR\n";
  }
  return s;
}

}  // namespace vmt::bench
