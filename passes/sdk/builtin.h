/* passes/builtin.h: registers every pass folder of passes/ into a registry.
 *
 * Declares: cg_builtin_passes_register.
 */
#ifndef CG_PASSES_BUILTIN_H
#define CG_PASSES_BUILTIN_H

#include <stdbool.h>

#include "cg/error.h"
#include "cg/fg.h"

bool cg_builtin_passes_register(fg_registry *registry, cg_error *err);

#endif
