/* libhorizon.so loaded at run time, as Julia's ccall and Python's ctypes do: no header-time
 * link, only the C symbols. Searches a random cloud and checks it against brute force.
 * Usage: dlopen_search /path/to/libhorizon.so.1 */
#include <dlfcn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include <horizon/horizon.h> /* for the struct and the codes only: nothing is linked */

int main(int argc, char** argv) {
  void* library = dlopen(argc > 1 ? argv[1] : "libhorizon.so.1", RTLD_NOW | RTLD_LOCAL);
  if (library == NULL) {
    fprintf(stderr, "dlopen: %s\n", dlerror());
    return 2;
  }
  void (*options_default)(horizon_options*) = (void (*)(horizon_options*))dlsym(library, "horizon_options_default");
  horizon_status (*search)(const double*, size_t, int, const horizon_options*, horizon_list**) =
      (horizon_status(*)(const double*, size_t, int, const horizon_options*, horizon_list**))dlsym(library, "horizon_search");
  const int64_t* (*offsets_of)(const horizon_list*) = (const int64_t* (*)(const horizon_list*))dlsym(library, "horizon_list_offsets");
  const int32_t* (*indices_of)(const horizon_list*) = (const int32_t* (*)(const horizon_list*))dlsym(library, "horizon_list_indices");
  void (*list_free)(horizon_list*) = (void (*)(horizon_list*))dlsym(library, "horizon_list_free");
  const char* (*version)(void) = (const char* (*)(void))dlsym(library, "horizon_version");
  if (!options_default || !search || !offsets_of || !indices_of || !list_free || !version) {
    fprintf(stderr, "dlsym: %s\n", dlerror());
    return 2;
  }

  enum { count = 2000 };
  static double xyz[3 * count];
  srand(7);
  for (int k = 0; k < 3 * count; ++k) xyz[k] = 10.0 * rand() / RAND_MAX;
  horizon_options options;
  options_default(&options);
  options.horizon = 1.0;
  horizon_list* list = NULL;
  if (search(xyz, count, 3, &options, &list) != HORIZON_OK) return 2;
  const int64_t* offsets = offsets_of(list);
  const int32_t* indices = indices_of(list);
  int mismatches = 0;
  for (int i = 0; i < count; ++i) {  /* brute force, in id order as the sorted rows */
    int64_t at = offsets[i];
    for (int j = 0; j < count; ++j) {
      const double dx = xyz[3 * j] - xyz[3 * i], dy = xyz[3 * j + 1] - xyz[3 * i + 1], dz = xyz[3 * j + 2] - xyz[3 * i + 2];
      if (j != i && (dx * dx + dy * dy) + dz * dz < 1.0) mismatches += at >= offsets[i + 1] || indices[at++] != j;
    }
    mismatches += at != offsets[i + 1];
  }
  printf("libhorizon %s through dlopen: %lld entries, %d mismatches against brute force\n", version(),
         (long long)offsets[count], mismatches);
  list_free(list);
  dlclose(library);
  return mismatches == 0 ? 0 : 1;
}
