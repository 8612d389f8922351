/* The families of a 20^3 lattice through the C API: the histogram of family sizes.
 * Build: cc families.c $(pkg-config --cflags --libs horizon) */
#include <stdio.h>
#include <stdlib.h>

#include <horizon/horizon.h>

int main(void) {
  const int n = 20;                      /* points per side, spacing 0.5 on a cube of side 10 */
  const size_t count = (size_t)n * n * n;
  double* xyz = malloc(3 * count * sizeof(double));
  for (size_t p = 0; p < count; ++p) {
    xyz[3 * p + 0] = (p % n + 0.5) * 0.5;
    xyz[3 * p + 1] = (p / n % n + 0.5) * 0.5;
    xyz[3 * p + 2] = (p / n / n + 0.5) * 0.5;
  }
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 3.015 * 0.5;        /* the peridynamics standard: m = 3.015 spacings */
  horizon_list* list = NULL;
  if (horizon_search(xyz, count, 3, &options, &list) != HORIZON_OK) {
    fprintf(stderr, "horizon: %s\n", horizon_last_error());
    return 2;
  }
  const int64_t* offsets = horizon_list_offsets(list);
  long histogram[200] = {0};
  for (size_t i = 0; i < count; ++i) histogram[offsets[i + 1] - offsets[i]] += 1;
  printf("horizon %s: %lld entries; family size: points\n", horizon_version(), (long long)horizon_list_total(list));
  for (int size = 0; size < 200; ++size)
    if (histogram[size] > 0) printf("%4d: %ld\n", size, histogram[size]);
  const int exact = horizon_list_total(list) == 816728 && histogram[122] > 0;  /* interior points: 122 */
  horizon_list_free(list);
  free(xyz);
  return exact ? 0 : 1;
}
