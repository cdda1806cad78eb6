// Every shared shading header, in dependency order. Included once per C++ lane type by
// instantiate.h (no include guards on purpose) and by the GLSL entry points.
#include "shade/prelude.h"
#include "shade/exact_math.h"
#include "shade/sampling.h"
#include "shade/brdf.h"
#include "shade/verify_kernels.h"
#include "shade/mip.h"
#include "shade/gbuffer.h"
#include "shade/shadow.h"
#include "shade/shade_mirror.h"
#include "shade/paraboloid.h"
#include "shade/sh_irradiance.h"
#include "shade/shade_fis.h"
