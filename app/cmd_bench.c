/* fogpipe bench STAGE: hands over to the bench library. */
#include "app/commands.h"
#include "bench/bench.h"

int cmd_bench(int argc, char **argv) { return bench_main(argc, argv); }
