// Twin of twinray_shared::random: the PCG hash (Jarzynski and Olano 2020), bit for bit.
#ifndef TWINRAY_RANDOM_GLSL
#define TWINRAY_RANDOM_GLSL

uint pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// Uniform in [0, 1): 24 random bits, exact in float.
float random(uint seed, uint pixel, uint sample_index, uint dimension) {
    uint h = pcg(dimension + pcg(sample_index + pcg(pixel + pcg(seed))));
    return float(h >> 8u) * (1.0 / 16777216.0);
}
#endif
