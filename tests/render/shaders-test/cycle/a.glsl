// a includes b, b includes a.
#include "b.glsl"
