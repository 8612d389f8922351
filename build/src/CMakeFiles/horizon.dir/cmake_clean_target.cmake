file(REMOVE_RECURSE
  "libhorizon.a"
)
