#pragma once
// The generated 1M-block programs the NC benchmarks share (nc_decode_bench, block_search_bench,
// generate_program): straight moves (MTC200), expressions and loops with subprogram calls (ISG).
// The straight and loop programs also come in RS274NGC, the same moves for LinuxCNC's rs274
// (bench/linuxcnc_compare.sh); each twin sits beside its vmt original so that they change
// together.

#include <cstdio>
#include <string>

namespace vmt::bench {

constexpr int kBlocks = 1000000;

// Block i of the straight program in both dialects: the same move, only the syntax differs.
inline void StraightMove(char* line, size_t size, int i) {
  std::snprintf(line, size, "N%04d G01 X%.3f Z%.3f F%d\n", i % 10000, 10 + (i % 977) * 0.125,
                -(i % 613) * 0.25, 500 + i % 7 * 100);
}

inline std::string StraightMtc200(int blocks = kBlocks) {
  std::string s;
  s.reserve(size_t(blocks) * 32);
  char line[96];
  for (int i = 0; i < blocks; ++i) {
    StraightMove(line, sizeof line, i);
    s += line;
  }
  return s;
}

/// The straight program for rs274: the same lines, and M2 because RS274NGC ends a program there.
inline std::string StraightRs274ngc(int blocks = kBlocks) {
  return StraightMtc200(blocks) + "M2\n";
}

inline std::string ExpressionsIsg(int blocks = kBlocks) {
  std::string s = "%expr\n";
  s.reserve(size_t(blocks) * 48);
  char line[128];
  for (int i = 0; i < blocks; ++i) {
    std::snprintf(line, sizeof line, "N%d P%d = [P%d + %d.5] * 2 / [1 + P%d] X[P%d * 0.5 - %d]\n",
                  i, i % 50 + 1, (i + 7) % 50 + 1, i % 13, (i + 3) % 50 + 1, i % 50 + 1, i % 31);
    s += line;
  }
  return s;
}

inline std::string LoopsIsg(int blocks = kBlocks) {
  // Loop and subprogram structure repeated: $FOR, $IF, $WHILE and L calls between moves.
  std::string s = "%loops\n";
  s.reserve(size_t(blocks) * 24);
  for (int i = 0; i < blocks / 10; ++i) {
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

/// The subprogram LoopsIsg calls (its own program in the ISG program store).
inline std::string LoopsIsgSubprogram() { return "%sub_a\nG01 Z1 F1000\nM17\n"; }

/// LoopsIsg in RS274NGC: $FOR becomes a counted o-word while (RS274NGC has no for), P1/P2 are
/// #1/#2, the subprogram is defined in the file (rs274 finds no program store). Every loop gets
/// its own o-word numbers: LinuxCNC matches an o-word's end by its number.
inline std::string LoopsRs274ngc(int blocks = kBlocks) {
  std::string s = "o<sub_a> sub\nG01 Z1 F1000\no<sub_a> endsub\n#2 = 0\n";
  s.reserve(size_t(blocks) * 30);
  char line[512];
  for (int i = 0; i < blocks / 10; ++i) {
    const int w = 3 * i + 1, c = 3 * i + 2, v = 3 * i + 3;
    std::snprintf(line, sizeof line,
                  "#1 = 1\n"
                  "o%d while [#1 LE 10]\n"
                  "o%d if [#1 EQ 5]\n"
                  "o<sub_a> call\n"
                  "o%d else\n"
                  "G01 X[#1] Y[#1 * 2] F1000\n"
                  "o%d endif\n"
                  "o%d while [#2 LT 3]\n"
                  "#2 = [#2 + 1]\n"
                  "o%d endwhile\n"
                  "#1 = [#1 + 1]\n"
                  "o%d endwhile\n",
                  w, c, c, c, v, v, w);
    s += line;
  }
  return s + "M2\n";
}

}  // namespace vmt::bench
