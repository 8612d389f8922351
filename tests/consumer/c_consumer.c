/* A C program outside the horizon tree, compiled by cc alone against the installed library. */
#include <horizon/horizon.h>
#include <stdio.h>
#include <string.h>

int main(void) {
  double xyz[3 * 27];
  for (int p = 0; p < 27; ++p) {
    xyz[3 * p] = p % 3;
    xyz[3 * p + 1] = p / 3 % 3;
    xyz[3 * p + 2] = p / 9;
  }
  horizon_options options;
  horizon_options_default(&options);
  options.horizon = 1.5;  /* face and edge neighbours of a 3x3x3 lattice of spacing 1 */
  horizon_list* list = NULL;
  if (horizon_search(xyz, 27, 3, &options, &list) != HORIZON_OK) {
    fprintf(stderr, "%s\n", horizon_last_error());
    return 1;
  }
  const long long total = (long long)horizon_list_total(list);
  horizon_list_free(list);
  printf("C consumer: horizon %s (header %s), %lld entries\n", horizon_version(), HORIZON_VERSION_STRING, total);
  return total == 2 * (54 + 72) && strcmp(horizon_version(), HORIZON_VERSION_STRING) == 0 ? 0 : 1;
}
