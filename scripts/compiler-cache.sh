# Sourced by the build scripts: compile through ccache when there is one, keyed on paths relative
# to this checkout (and not on the build directory's), so that a fresh clone, as CI makes each run,
# reuses the objects of the last one instead of compiling everything again.
cache_flags=()
if command -v ccache > /dev/null; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  cache_flags=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi
