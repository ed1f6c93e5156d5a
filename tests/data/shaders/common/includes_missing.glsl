// includes_missing.glsl: line 2 includes a file that does not exist.
#include "common/does_not_exist.glsl"
