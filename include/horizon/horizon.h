/* horizon.h: horizon's C API, for C99 (and anything that calls C: Fortran, Julia, Python's ctypes).
 *
 * Every function returns a horizon_status; on failure horizon_last_error() gives a message that
 * names the cause (the point, the option, the bytes needed), as the command line does. No C++
 * exception crosses this interface. Lists and Verlet lists are opaque handles that the caller
 * frees; inputs are never modified. The only global state is the thread-local error message.
 *
 *   horizon_options options;
 *   horizon_options_default(&options);
 *   options.horizon = 0.3;
 *   horizon_list* list = NULL;
 *   if (horizon_search(xyz, n, 3, &options, &list) != HORIZON_OK) puts(horizon_last_error());
 *   const int64_t* offsets = horizon_list_offsets(list);    // n + 1 row offsets
 *   const int32_t* indices = horizon_list_indices(list);    // row i: indices[offsets[i] .. offsets[i+1])
 *   horizon_list_free(list);
 */
#ifndef HORIZON_H
#define HORIZON_H

#include <stddef.h>
#include <stdint.h>

#include "horizon/version.h"

#if defined(_WIN32)
#define HORIZON_API
#else
#define HORIZON_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/** What a call returned. */
typedef enum {
  HORIZON_OK = 0,
  HORIZON_INVALID_INPUT = 1,         /**< bad points, radii, options or arguments (NaN, horizon <= 0, NULL, ...) */
  HORIZON_OUT_OF_MEMORY = 2,         /**< an allocation failed */
  HORIZON_LIST_TOO_LARGE = 3,        /**< the list would not fit in the host memory allowed (max_memory) */
  HORIZON_BACKEND_UNAVAILABLE = 4,   /**< the backend asked for is not built or has no hardware here */
  HORIZON_DEVICE_OUT_OF_MEMORY = 5,  /**< the list does not fit in GPU memory */
  HORIZON_INTERNAL_ERROR = 6         /**< anything else: a bug, please report it with the message */
} horizon_status;

typedef enum { HORIZON_METRIC_L2 = 0, HORIZON_METRIC_L1 = 1, HORIZON_METRIC_LINF = 2 } horizon_metric;

typedef enum {
  HORIZON_BACKEND_AUTO = 0,
  HORIZON_BACKEND_SERIAL = 1,
  HORIZON_BACKEND_OPENMP = 2,
  HORIZON_BACKEND_CUDA = 3
} horizon_backend;

/** Which radius a pair i-j is tested with when every point has its own (horizon_search_radii). */
typedef enum {
  HORIZON_RADIUS_GATHER = 0,   /**< d < r_i */
  HORIZON_RADIUS_SCATTER = 1,  /**< d < r_j */
  HORIZON_RADIUS_MAX = 2,      /**< d < max(r_i, r_j) */
  HORIZON_RADIUS_MIN = 3       /**< d < min(r_i, r_j) */
} horizon_radius_rule;

/** Search options. Fill with horizon_options_default(), then set what you need. `size` comes
 *  first so that later versions can add fields at the end without breaking callers built
 *  against this one: the library reads only the fields that fit in `size` bytes. */
typedef struct {
  size_t size;              /**< sizeof(horizon_options), set by horizon_options_default() */
  double horizon;           /**< pairs closer than this (strictly) are neighbours */
  int32_t metric;           /**< horizon_metric (default L2) */
  int32_t cells_per_horizon;/**< k: cell side horizon/k, 1-3 (default 1) */
  int32_t half;             /**< nonzero: each pair once, in the row of the smaller id */
  int32_t sort_rows;        /**< nonzero (default): rows ascending by id */
  int32_t backend;          /**< horizon_backend (default AUTO) */
  int32_t threads;          /**< openmp threads, 0: all cores */
  int32_t device;           /**< CUDA device */
  int32_t reserved;         /**< 0 */
  double box[3];            /**< periods of a periodic box, 0: open axis (default all 0) */
  uint64_t max_memory;      /**< most bytes of host memory the list may take, 0: what is available */
  uint64_t gpu_max_memory;  /**< most bytes of GPU memory a search may take, 0: what is free */
} horizon_options;

/** A neighbour list in compressed sparse rows (host memory), owned by horizon. */
typedef struct horizon_list horizon_list;
/** A neighbour list in GPU memory (horizon_search_device). */
typedef struct horizon_device_list horizon_device_list;
/** A Verlet list for moving points. */
typedef struct horizon_verlet horizon_verlet;

/** The version of the linked library, "MAJOR.MINOR.PATCH" (the header's is HORIZON_VERSION_STRING). */
HORIZON_API const char* horizon_version(void);
/** The message of the last failed call on this thread ("" if none). Valid until the next call. */
HORIZON_API const char* horizon_last_error(void);
/** Fills `options` with the defaults (and its size). */
HORIZON_API void horizon_options_default(horizon_options* options);
/** Whether a backend is built and has hardware here (1) or not (0). */
HORIZON_API int horizon_backend_available(horizon_backend backend);

/** The neighbour list of `n` points (x y [z] per point, `dims` 2 or 3) against themselves. */
HORIZON_API horizon_status horizon_search(const double* points, size_t n, int dims, const horizon_options* options,
                                          horizon_list** list);
/** The same with one radius per point combined by `rule`; options->horizon is ignored. Half lists
 *  only with the max and min rules. */
HORIZON_API horizon_status horizon_search_radii(const double* points, size_t n, int dims, const double* radii,
                                                horizon_radius_rule rule, const horizon_options* options,
                                                horizon_list** list);
/** The families of `n_queries` query points among `n_references` reference points: row q holds
 *  every reference within options->horizon of query q or, when `radii` is not NULL, within
 *  radii[q]. Ids index the references; nothing is excluded as self. Full lists only. */
HORIZON_API horizon_status horizon_search_queries(const double* queries, size_t n_queries, const double* references,
                                                  size_t n_references, int dims, const double* radii,
                                                  const horizon_options* options, horizon_list** list);

HORIZON_API size_t horizon_list_size(const horizon_list* list);             /**< rows (points) */
HORIZON_API int64_t horizon_list_total(const horizon_list* list);           /**< entries */
HORIZON_API const int64_t* horizon_list_offsets(const horizon_list* list);  /**< size + 1 offsets */
HORIZON_API const int32_t* horizon_list_indices(const horizon_list* list);  /**< total ids */
HORIZON_API int horizon_list_is_half(const horizon_list* list);
/** Adds 1 to every offset and id in place, for codes that index from 1 (Fortran): row i
 *  (1-based) is then indices[offsets[i-1]-1 .. offsets[i]-1) in C, indices(offsets(i):offsets(i+1)-1)
 *  in Fortran. A one-based list can no longer be filtered. */
HORIZON_API horizon_status horizon_list_make_one_based(horizon_list* list);
HORIZON_API int horizon_list_is_one_based(const horizon_list* list);
HORIZON_API void horizon_list_free(horizon_list* list);

/** Drops, in place, every bond of `list` (a list of `points`, n x dims) that crosses one of the
 *  Peridigm shapes given as JSON (an array of rectangles and disks; see the bond filters guide). */
HORIZON_API horizon_status horizon_filter_bonds(horizon_list* list, const double* points, size_t n, int dims,
                                                const char* filters_json, int threads);
/** Keeps, in place, only the bonds between the block pairs given as text ("1-1,1-2,2-2"),
 *  `blocks` giving each of the list's points its block. */
HORIZON_API horizon_status horizon_filter_blocks(horizon_list* list, const int32_t* blocks, const char* pairs,
                                                 int threads);

/** A Verlet list of `n` points: one search within options->horizon + skin. */
HORIZON_API horizon_status horizon_verlet_create(const double* points, size_t n, int dims,
                                                 const horizon_options* options, double skin, horizon_verlet** verlet);
/** Sets *needed to 1 once a point of `points` (the same n points, moved) has moved by skin / 2. */
HORIZON_API horizon_status horizon_verlet_needs_rebuild(const horizon_verlet* verlet, const double* points, size_t n,
                                                        int* needed);
/** The exact list of the moved `points` within the horizon, from the stored candidates. */
HORIZON_API horizon_status horizon_verlet_refresh(const horizon_verlet* verlet, const double* points, size_t n,
                                                  horizon_list** list);
HORIZON_API void horizon_verlet_free(horizon_verlet* verlet);

/** Points already in GPU memory (`device_points`, x y [z] per point, float64, on device
 *  options->device) searched on `stream` (a cudaStream_t, NULL: the default stream); the list
 *  stays on the GPU. HORIZON_BACKEND_UNAVAILABLE in builds without CUDA. */
HORIZON_API horizon_status horizon_search_device(const double* device_points, size_t n, int dims,
                                                 const horizon_options* options, void* stream,
                                                 horizon_device_list** list);
HORIZON_API size_t horizon_device_list_size(const horizon_device_list* list);
HORIZON_API int64_t horizon_device_list_total(const horizon_device_list* list);
HORIZON_API const int64_t* horizon_device_list_offsets(const horizon_device_list* list);  /**< device pointer */
HORIZON_API const int32_t* horizon_device_list_indices(const horizon_device_list* list);  /**< device pointer */
/** Frees the list's GPU memory, ordered on the stream it was built on. */
HORIZON_API void horizon_device_list_free(horizon_device_list* list);

#ifdef __cplusplus
}
#endif

#endif /* HORIZON_H */
