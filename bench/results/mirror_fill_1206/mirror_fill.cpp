// Prototype (not part of the build): is a fill that tests each pair once (the upper half
// stencil) and writes every hit into both rows faster than the full-stencil fill that tests
// each pair twice? Lattice n^3 in raster order, cell side = horizon, points sorted by cell (SoA),
// AVX-512, rows unsorted and written straight into place by both variants; offsets from one
// count pass shared by both. Prints each variant's median and checks they hold the same rows.
//   g++ -O2 -std=c++20 -march=native bench/results/mirror_fill_1206/mirror_fill.cpp -o /tmp/mirror_fill
//   /tmp/mirror_fill [n=100] [m=1.5] [reps=7]
#include <immintrin.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

using Clock = std::chrono::steady_clock;

struct Cells {
  int nx, ny, nz;  // padded by one cell each side, so every stencil cell exists
  std::vector<std::int64_t> start;  // nx*ny*nz + 1
  std::vector<double> x, y, z;      // sorted by cell, padded by 8
  std::vector<std::int32_t> id;
  std::int64_t cell(int cx, int cy, int cz) const { return (static_cast<std::int64_t>(cz) * ny + cy) * nx + cx; }
};

static Cells bin(int n, double spacing, double h) {
  Cells c;
  const int per = static_cast<int>(n * spacing / h) + 1;
  c.nx = c.ny = c.nz = per + 2;
  const std::int64_t cells = static_cast<std::int64_t>(c.nx) * c.ny * c.nz, N = static_cast<std::int64_t>(n) * n * n;
  std::vector<std::int64_t> key(N);
  std::vector<std::int64_t> count(cells + 1, 0);
  for (std::int64_t i = 0; i < N; ++i) {
    const int ix = i % n, iy = i / n % n, iz = i / n / n;
    const int cx = static_cast<int>(ix * spacing / h) + 1, cy = static_cast<int>(iy * spacing / h) + 1,
              cz = static_cast<int>(iz * spacing / h) + 1;
    key[i] = c.cell(cx, cy, cz);
    ++count[key[i] + 1];
  }
  for (std::int64_t k = 0; k < cells; ++k) count[k + 1] += count[k];
  c.start = count;
  c.x.assign(N + 8, 1e300), c.y.assign(N + 8, 1e300), c.z.assign(N + 8, 1e300), c.id.assign(N + 8, -1);
  for (std::int64_t i = 0; i < N; ++i) {
    const std::int64_t at = count[key[i]]++;
    c.x[at] = (i % n) * spacing, c.y[at] = (i / n % n) * spacing, c.z[at] = (i / n / n) * spacing;
    c.id[at] = static_cast<std::int32_t>(i);
  }
  return c;
}

// Hits of point p (coordinates px, py, pz) among sorted positions [b, e): a bit per candidate.
struct Soa {  // the sorted arrays as plain pointers, so that loops hold them in registers
  const double *x, *y, *z;
  const std::int32_t* id;
};

template <class F>
static inline void test_run(const Soa& c, __m512d px, __m512d py, __m512d pz, __m512d h2, std::int64_t b,
                            std::int64_t e, F&& on_hits) {
  for (std::int64_t q = b; q < e; q += 8) {
    const __m512d dx = _mm512_sub_pd(px, _mm512_loadu_pd(c.x + q)), dy = _mm512_sub_pd(py, _mm512_loadu_pd(c.y + q)),
                  dz = _mm512_sub_pd(pz, _mm512_loadu_pd(c.z + q));
    const __m512d d2 = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_mul_pd(dx, dx)));
    __mmask8 hit = _mm512_cmp_pd_mask(d2, h2, _CMP_LT_OQ);
    if (e - q < 8) hit &= static_cast<__mmask8>((1u << (e - q)) - 1);
    on_hits(q, hit);
  }
}

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const double m = argc > 2 ? std::atof(argv[2]) : 1.5;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 7;
  const double spacing = 0.1, h = m * spacing;
  const Cells cells = bin(n, spacing, h);
  const Cells& c = cells;
  const Soa soa{cells.x.data(), cells.y.data(), cells.z.data(), cells.id.data()};
  const std::int64_t N = static_cast<std::int64_t>(n) * n * n;
  const __m512d h2 = _mm512_set1_pd(h * h);

  // The runs of a cell's full stencil (9 runs of 3 cells along x) and of its upper half (the
  // cells after it: the rest of its own cell and cell x+1 as one run, row y+1, plane z+1).
  auto full_runs = [&](int cx, int cy, int cz, std::int64_t* r) {
    int k = 0;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy) {
        r[k++] = c.start[c.cell(cx - 1, cy + dy, cz + dz)];
        r[k++] = c.start[c.cell(cx + 1, cy + dy, cz + dz) + 1];
      }
    return k / 2;
  };
  auto upper_runs = [&](int cx, int cy, int cz, std::int64_t* r) {  // r[0] is replaced by p + 1
    int k = 0;
    r[k++] = 0, r[k++] = c.start[c.cell(cx + 1, cy, cz) + 1];
    r[k++] = c.start[c.cell(cx - 1, cy + 1, cz)], r[k++] = c.start[c.cell(cx + 1, cy + 1, cz) + 1];
    for (int dy = -1; dy <= 1; ++dy)
      r[k++] = c.start[c.cell(cx - 1, cy + dy, cz + 1)], r[k++] = c.start[c.cell(cx + 1, cy + dy, cz + 1) + 1];
    return k / 2;
  };
  auto each_point = [&](auto&& f) {
    for (int cz = 1; cz < c.nz - 1; ++cz)
      for (int cy = 1; cy < c.ny - 1; ++cy)
        for (int cx = 1; cx < c.nx - 1; ++cx) {
          const std::int64_t cell = c.cell(cx, cy, cz);
          if (c.start[cell] != c.start[cell + 1]) f(cx, cy, cz, c.start[cell], c.start[cell + 1]);
        }
  };

  // Count (full stencil), rows by sorted position.
  std::vector<std::int64_t> offsets(N + 1, 0);
  each_point([&](int cx, int cy, int cz, std::int64_t b, std::int64_t e) {
    std::int64_t r[18];
    const int runs = full_runs(cx, cy, cz, r);
    for (std::int64_t p = b; p < e; ++p) {
      const __m512d px = _mm512_set1_pd(c.x[p]), py = _mm512_set1_pd(c.y[p]), pz = _mm512_set1_pd(c.z[p]);
      std::int64_t found = -1;  // itself
      for (int k = 0; k < runs; ++k)
        test_run(soa, px, py, pz, h2, r[2 * k], r[2 * k + 1],
                 [&](std::int64_t, __mmask8 hit) { found += __builtin_popcount(hit); });
      offsets[p + 1] = found;
    }
  });
  for (std::int64_t p = 0; p < N; ++p) offsets[p + 1] += offsets[p];
  std::vector<std::int32_t> full(offsets[N] + 16), mirror(offsets[N] + 16);
  std::vector<std::int64_t> cursor(N);

  // The full-stencil fill into `rows`; `pack(hit, ids, out)` stores the hit lanes of ids at out.
  auto fill_full_stencil = [&](std::vector<std::int32_t>& rows, auto pack) {
    each_point([&](int cx, int cy, int cz, std::int64_t b, std::int64_t e) {
      std::int64_t r[18];
      const int runs = full_runs(cx, cy, cz, r);
      for (std::int64_t p = b; p < e; ++p) {
        const __m512d px = _mm512_set1_pd(c.x[p]), py = _mm512_set1_pd(c.y[p]), pz = _mm512_set1_pd(c.z[p]);
        const __m256i self = _mm256_set1_epi32(c.id[p]);
        std::int32_t* out = &rows[offsets[p]];
        for (int k = 0; k < runs; ++k)
          test_run(soa, px, py, pz, h2, r[2 * k], r[2 * k + 1], [&](std::int64_t q, __mmask8 hit) {
            const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(soa.id + q));
            hit &= _mm256_cmpneq_epi32_mask(ids, self);
            pack(hit, ids, out);
            out += __builtin_popcount(hit);
          });
      }
    });
  };
  // Hits packed by the register compress, or by a permute with indices from a table of 256.
  static const auto table = [] {
    std::vector<std::int32_t> t(256 * 8);
    for (int mask = 0; mask < 256; ++mask) {
      int out = 0;
      for (int lane = 0; lane < 8; ++lane)
        if (mask >> lane & 1) t[mask * 8 + out++] = lane;
      for (; out < 8; ++out) t[mask * 8 + out] = 0;
    }
    return t;
  }();
  std::vector<std::int32_t> permuted(offsets[N] + 16);
  auto fill_full = [&]() __attribute__((noinline)) {
    fill_full_stencil(full, [](__mmask8 hit, __m256i ids, std::int32_t* out) {
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_maskz_compress_epi32(hit, ids));
    });
  };
  auto fill_permute = [&]() __attribute__((noinline)) {
    fill_full_stencil(permuted, [](__mmask8 hit, __m256i ids, std::int32_t* out) {
      const __m256i index = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&table[hit * 8]));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_permutevar8x32_epi32(ids, index));
    });
  };
  auto fill_mirror = [&]() __attribute__((noinline)) {
    std::copy(offsets.begin(), offsets.end() - 1, cursor.begin());
    each_point([&](int cx, int cy, int cz, std::int64_t b, std::int64_t e) {
      std::int64_t r[10];
      const int runs = upper_runs(cx, cy, cz, r);
      for (std::int64_t p = b; p < e; ++p) {
        const __m512d px = _mm512_set1_pd(c.x[p]), py = _mm512_set1_pd(c.y[p]), pz = _mm512_set1_pd(c.z[p]);
        const std::int32_t self = c.id[p];
        std::int32_t* out = &mirror[cursor[p]];
        r[0] = p + 1;
        for (int k = 0; k < runs; ++k)
          test_run(soa, px, py, pz, h2, r[2 * k], r[2 * k + 1], [&](std::int64_t q, __mmask8 hit) {
            // A masked store: a plain one would run into the next row, which may hold hits already.
            const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(soa.id + q));
            const int hits = __builtin_popcount(hit);
            _mm256_mask_storeu_epi32(out, static_cast<__mmask8>((1u << hits) - 1), _mm256_maskz_compress_epi32(hit, ids));
            out += hits;
            for (unsigned bits = hit; bits; bits &= bits - 1) mirror[cursor[q + __builtin_ctz(bits)]++] = self;
          });
        cursor[p] = out - mirror.data();
      }
    });
  };

  auto time = [&](auto&& f) {
    std::vector<double> t;
    for (int i = 0; i < reps; ++i) {
      const auto t0 = Clock::now();
      f();
      t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::sort(t.begin(), t.end());
    return t;
  };
  for (int round = 0; round < 2; ++round) {
    const auto a = time(fill_full), b = time(fill_mirror), l = time(fill_permute);
    std::printf("  permute from a table instead of compress: min %.1f med %.1f ms\n", l.front(), l[l.size() / 2]);
    std::printf("n=%d m=%g entries=%lld: full stencil fill min %.1f med %.1f ms; upper half + mirror min %.1f med %.1f ms\n",
                n, m, static_cast<long long>(offsets[N]), a.front(), a[a.size() / 2], b.front(), b[b.size() / 2]);
  }
  for (std::int64_t p = 0; p < N; ++p) {
    std::sort(&full[offsets[p]], &full[offsets[p + 1]]);
    std::sort(&mirror[offsets[p]], &mirror[offsets[p + 1]]);
  }
  for (std::int64_t p = 0; p < N; ++p) std::sort(&permuted[offsets[p]], &permuted[offsets[p + 1]]);
  const bool same = std::equal(full.begin(), full.begin() + offsets[N], mirror.begin()) &&
                    std::equal(full.begin(), full.begin() + offsets[N], permuted.begin());
  std::printf("same rows: %s\n", same ? "yes" : "NO");
  return same ? 0 : 1;
}
