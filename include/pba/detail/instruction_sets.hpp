#pragma once
// A function compiled once for each instruction set, the best picked when the program starts:
// AVX-512 (x86-64-v4), AVX2 with FMA (x86-64-v3) and the baseline, so that the default build runs
// the widest vectors a CPU has without -march=native. GCC on x86-64 only: clang 14 does not
// combine target_clones with flatten, and other CPUs have other instruction sets (there the
// function is compiled once, for the build's target). PBA_FOR_EACH_INSTRUCTION_SET also inlines
// every call into each copy (the swarm's step: its kernels compiled for that instruction set).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define PBA_TARGET_CLONES [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#define PBA_FOR_EACH_INSTRUCTION_SET [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"), gnu::flatten]]
#else
#define PBA_TARGET_CLONES
#define PBA_FOR_EACH_INSTRUCTION_SET
#endif
