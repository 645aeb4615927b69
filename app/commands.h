/* Entry points of the fogpipe commands, one per app/cmd_<name>.c. */
#ifndef FOGPIPE_APP_COMMANDS_H
#define FOGPIPE_APP_COMMANDS_H

#define FOG_COMMAND(name, summary) int cmd_##name(int argc, char **argv);
#include "app/commands.def"
#undef FOG_COMMAND

#endif
