#include "app/cli.h"

int main(int argc, char** argv) {
    return busdecode::runCli(argc, argv);
}
