// b includes a again.
#include "a.glsl"
