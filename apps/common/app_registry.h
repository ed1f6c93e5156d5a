/* apps/common/app_registry.h: the pass registry every app uses: the built-in passes,
 * then the plugins of $CONEGRAPH_PLUGIN_PATH, then those named with --plugin.
 *
 * Declares: app_registry_create.
 */
#ifndef CONEGRAPH_APP_REGISTRY_H
#define CONEGRAPH_APP_REGISTRY_H

#include "cg/error.h"
#include "cg/fg.h"

/* NULL with err filled when a plugin cannot be loaded. */
fg_registry *app_registry_create(const char *const *plugins, int plugin_count, cg_error *err);

#endif
