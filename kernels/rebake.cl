// Deformable bodies (paper Fig. 17): re-bake positions and area vectors of one mesh's samples from
// animated vertex positions through the fixed texel → (triangle, weight, barycentric) map
// (plugin/BulletBuoyancy/bake/DeformableRebake.h; per-piece formula bb_rebake_piece in SampleFormulas.h).
// vertices: 3 reals per vertex; triangles: 3 ints per triangle; pieceStart: nsamples + 1 offsets into
// pieceTri / pieceData (3 reals per piece: weight, β1, β2). Writes BB_SAMPLE_STRIDE reals per sample, from
// sample slot firstSample of `out` on (the mesh's place in the backend's sample buffer).
__kernel void bb_rebake(__global const bb_real* vertices, __global const int* triangles,
                        __global const int* pieceStart, __global const int* pieceTri,
                        __global const bb_real* pieceData, int nsamples, int firstSample,
                        __global bb_real* out) {
    const int s = get_global_id(0);
    if (s >= nsamples) return;
    bb_real acc[7] = {0, 0, 0, 0, 0, 0, 0};
    for (int k = pieceStart[s]; k < pieceStart[s + 1]; ++k) {
        const int t = pieceTri[k];
        bb_real a[3], b[3], c[3];
        for (int j = 0; j < 3; ++j) {
            a[j] = vertices[3 * triangles[3 * t] + j];
            b[j] = vertices[3 * triangles[3 * t + 1] + j];
            c[j] = vertices[3 * triangles[3 * t + 2] + j];
        }
        bb_rebake_piece(a, b, c, pieceData[3 * k], pieceData[3 * k + 1], pieceData[3 * k + 2], acc);
    }
    __global bb_real* S = out + (long)(firstSample + s) * BB_SAMPLE_STRIDE;
    const bb_real inv = acc[3] > 0 ? (bb_real)1 / acc[3] : (bb_real)0;
    S[0] = acc[4] * inv;
    S[1] = acc[5] * inv;
    S[2] = acc[6] * inv;
    S[3] = acc[0];
    S[4] = acc[1];
    S[5] = acc[2];
    S[6] = acc[3];
    for (int k = 7; k < BB_SAMPLE_STRIDE; ++k) S[k] = 0;
}
