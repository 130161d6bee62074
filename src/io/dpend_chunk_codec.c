/* One chunk of a chunked HDF5 dataset encoded as HDF5's filter pipeline
 * shuffle -> deflate -> Fletcher-32 stores it, so that dpend_hdf5 can encode the
 * chunks of a dataset on every thread and write each as stored (H5Dwrite_chunk).
 * HDF5's own filters run in the one thread that calls it. The bytes are those of
 * HDF5's filters (H5Zshuffle.c, H5Zdeflate.c, H5Zfletcher32.c, H5checksum.c):
 *   shuffle     byte b of element k goes to b*n + k (n elements of `esize` bytes)
 *   deflate     one zlib stream, as H5Z_filter_deflate's compress2 makes, which
 *               HDF5 (any inflate) reads whatever the settings that made it; here
 *               either zlib's default strategy at `level` (HDF5's own bytes) or,
 *               by plane (`deflate_planes`), each shuffled byte plane run-length
 *               coded or stored, whichever its entropy says
 *   Fletcher-32 of the deflated bytes, appended little-endian (UINT32ENCODE)
 * Also the CRC-32 of a block of bytes (dpend_checksum: the sweep's working file).
 * HDF5 reads such a chunk through its filters and checks its checksum, so a chunk
 * encoded wrongly is refused on reading, never read as other values. Pure
 * functions of their arguments: safe on any thread. Called from dpend_hdf5_write
 * through bind(C) interfaces; every function returns 0 or a positive error code. */
/* fpm compiles C files with no optimisation flag (its --flag is Fortran's): the
 * loops here are optimised whatever the build */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("O2")
#endif
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

/* HDF5's Fletcher-32 (H5_checksum_fletcher32): 16-bit big-endian words, an odd
 * last byte as the high byte of a word, sums folded every 360 words. */
static uint32_t fletcher32(const unsigned char *data, size_t nbytes)
{
    size_t len = nbytes / 2;
    uint32_t sum1 = 0, sum2 = 0;
    while (len) {
        size_t tlen = len > 360 ? 360 : len;
        len -= tlen;
        do {
            sum1 += (uint32_t)(((uint16_t)data[0]) << 8) | ((uint16_t)data[1]);
            data += 2;
            sum2 += sum1;
        } while (--tlen);
        sum1 = (sum1 & 0xffff) + (sum1 >> 16);
        sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    }
    if (nbytes % 2) {
        sum1 += (uint32_t)(((uint16_t)*data) << 8);
        sum2 += sum1;
        sum1 = (sum1 & 0xffff) + (sum1 >> 16);
        sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    }
    sum1 = (sum1 & 0xffff) + (sum1 >> 16);
    sum2 = (sum2 & 0xffff) + (sum2 >> 16);
    return (sum2 << 16) | sum1;
}

/* v[k] byte b becomes v[b] byte k (little-endian words: byte b = bits 8b..8b+7):
 * three rounds of swapping blocks across the diagonal (4x4 of bytes, 2x2, 1x1). */
static void transpose8(uint64_t v[8])
{
    for (int k = 0; k < 4; k++) {   /* 4-byte blocks: v[k] high half <-> v[k+4] low half */
        uint64_t t = ((v[k] >> 32) ^ v[k + 4]) & 0x00000000FFFFFFFFull;
        v[k] ^= t << 32;
        v[k + 4] ^= t;
    }
    for (int k = 0; k < 8; k += 4)   /* 2-byte blocks within each half */
        for (int j = k; j < k + 2; j++) {
            uint64_t t = ((v[j] >> 16) ^ v[j + 2]) & 0x0000FFFF0000FFFFull;
            v[j] ^= t << 16;
            v[j + 2] ^= t;
        }
    for (int j = 0; j < 8; j += 2) {   /* single bytes */
        uint64_t t = ((v[j] >> 8) ^ v[j + 1]) & 0x00FF00FF00FF00FFull;
        v[j] ^= t << 8;
        v[j + 1] ^= t;
    }
}

/* Byte b of element i of `from` (`rows` elements of `esize` bytes) to
 * to[b*n + i]: one column of a chunk of n elements, shuffled. Elements of 4 and 8
 * bytes are read whole, each byte written to its own sequential stream. */
static void shuffle_column(const unsigned char *from, int64_t rows, int esize,
                           unsigned char *to, int64_t n)
{
    const int little = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__;   /* byte b = v >> 8b */
    if (little && esize == 8) {
        int64_t i = 0;
        for (; i + 8 <= rows; i += 8) {   /* 8 elements: an 8 x 8 byte transpose */
            uint64_t v[8];
            memcpy(v, from + 8 * i, 64);
            transpose8(v);
            for (int b = 0; b < 8; b++) memcpy(to + b * n + i, &v[b], 8);
        }
        for (; i < rows; i++) {
            uint64_t v;
            memcpy(&v, from + 8 * i, 8);
            for (int b = 0; b < 8; b++) to[b * n + i] = (unsigned char)(v >> (8 * b));
        }
    } else if (little && esize == 4) {
        for (int64_t i = 0; i < rows; i++) {
            uint32_t v;
            memcpy(&v, from + 4 * i, 4);
            for (int b = 0; b < 4; b++) to[b * n + i] = (unsigned char)(v >> (8 * b));
        }
    } else {
        for (int b = 0; b < esize; b++)
            for (int64_t i = 0; i < rows; i++) to[b * n + i] = from[i * esize + b];
    }
}

/* Bits per byte of the order-0 entropy of the n bytes at p (n < 2^32), estimated
 * from every `stride`-th byte (the estimate is low by about 255/(2 m ln 2) bits for
 * m bytes counted: 0.02 bits for a plane of 32 kB counted one byte in four). */
static double plane_entropy(const unsigned char *p, int64_t n, int64_t stride)
{
    uint32_t part[4][256] = {{0}};   /* four counts: a run of one byte value is
                                         not one chain of dependent increments */
    int64_t i = 0, m = 0;
    for (; i + 3 * stride < n; i += 4 * stride, m += 4) {
        part[0][p[i]]++;
        part[1][p[i + stride]]++;
        part[2][p[i + 2 * stride]]++;
        part[3][p[i + 3 * stride]]++;
    }
    for (; i < n; i += stride, m++) part[0][p[i]]++;
    double h = 0;
    for (int c = 0; c < 256; c++) {
        double count = (double)part[0][c] + part[1][c] + part[2][c] + part[3][c];
        if (count > 0) h -= count * log2(count / (double)m);
    }
    return h / (double)m;
}

/* The `esize` planes of n bytes at `planes` deflated as one zlib stream into dst
 * (`cap` bytes), its length to *out. `by_plane` zero: zlib's default strategy at
 * `level` for the whole, as HDF5's filter. Nonzero: each plane with the run-length
 * strategy at `level`, or stored (level 0) when its bytes carry more than
 * `stored_bits` bits each (the low bytes of most numbers: Huffman codes would
 * save at most 2.5 % of them, at the cost of compressing them). One stream
 * either way; inflate reads it as any other. Returns 0, 1 out of memory, 2 a
 * zlib failure. */
static int deflate_planes(const unsigned char *planes, int64_t n, int esize, int level,
                          int by_plane, unsigned char *dst, int64_t cap, uLong *out)
{
    const double stored_bits = 7.8;
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    int z = deflateInit2(&zs, level, Z_DEFLATED, 15, 8, by_plane ? Z_RLE : Z_DEFAULT_STRATEGY);
    if (z != Z_OK) return z == Z_MEM_ERROR ? 1 : 2;
    zs.next_out = dst;
    zs.avail_out = (uInt)cap;
    int stored = 0;   /* the planes go in stored now */
    for (int b = 0; b < (by_plane ? esize : 1) && z == Z_OK; b++) {
        const unsigned char *p = planes + (int64_t)b * n;
        if (by_plane) {
            const int64_t stride = n >= 32768 ? 4 : n >= 16384 ? 2 : 1;   /* 8192 counted */
            int random = level > 0 && plane_entropy(p, n, stride) > stored_bits;
            if (random != stored) z = deflateParams(&zs, random ? 0 : level, Z_RLE);
            stored = random;
            if (z != Z_OK) break;
        }
        const int last = !by_plane || b == esize - 1;
        zs.next_in = (Bytef *)p;
        zs.avail_in = (uInt)(by_plane ? n : n * esize);
        z = deflate(&zs, last ? Z_FINISH : Z_NO_FLUSH);
        if (last) z = z == Z_STREAM_END ? Z_OK : Z_BUF_ERROR;
        else if (z == Z_OK && zs.avail_in != 0) z = Z_BUF_ERROR;
    }
    *out = zs.total_out;
    deflateEnd(&zs);
    return z == Z_OK ? 0 : z == Z_MEM_ERROR ? 1 : 2;
}

/* The CRC-32 (zlib's, as gzip and PNG use) of the n bytes at p. */
int64_t dpend_crc32(const unsigned char *p, int64_t n)
{
    uLong crc = crc32(0L, Z_NULL, 0);
    while (n > 0) {
        uInt step = n > (1 << 30) ? (1u << 30) : (uInt)n;
        crc = crc32(crc, p, step);
        p += step;
        n -= step;
    }
    return (int64_t)crc;
}

/* The most bytes an encoded chunk of `nbytes` raw bytes takes: zlib's bound, a
 * block's end and a stored block's header for each of up to 16 planes, the
 * checksum. */
int64_t dpend_chunk_bound(int64_t nbytes)
{
    return (int64_t)compressBound((uLong)nbytes) + 16 * 16 + 4;
}

/* Encode the chunk of the column-major n1 x n2 array at `base` (elements of
 * `esize` bytes) whose first element is (i0, j0), 0-based, and whose shape is
 * c1 x c2; the part of the chunk beyond the array (an edge chunk) is zeros, as
 * HDF5 never shows it. A rank-1 array is n1 x 1 with chunks c1 x 1. `by_plane`:
 * see deflate_planes. With `sum` nonzero the Fletcher-32 checksum is appended.
 * `work` has room for the chunk's c1*c2*esize bytes. The encoded bytes go to `dst`
 * (room for `cap` bytes, dpend_chunk_bound), their number to `*len`.
 * Returns 0, 1 out of memory, 2 a zlib failure (e.g. `cap` too small), 3 bad
 * arguments. */
int dpend_chunk_encode(const unsigned char *base, int64_t n1, int64_t n2, int64_t i0,
                       int64_t j0, int64_t c1, int64_t c2, int esize, int level,
                       int by_plane, int sum, unsigned char *work, unsigned char *dst,
                       int64_t cap, int64_t *len)
{
    if (n1 < 1 || n2 < 1 || c1 < 1 || c2 < 1 || i0 < 0 || j0 < 0 || i0 >= n1 || j0 >= n2 ||
        esize < 1 || esize > 16 || level < 0 || level > 9 || cap < 4 ||
        n1 * n2 > INT64_MAX / esize ||
        c1 * c2 * esize > (int64_t)UINT32_MAX)
        return 3;
    const int64_t n = c1 * c2;              /* elements in the chunk */
    const int64_t rows = n1 - i0 < c1 ? n1 - i0 : c1;  /* of the array in the chunk */
    const int64_t cols = n2 - j0 < c2 ? n2 - j0 : c2;
    unsigned char *shuffled = work;
    if (rows < c1 || cols < c2) memset(shuffled, 0, (size_t)(n * esize));
    for (int64_t j = 0; j < cols; j++)
        shuffle_column(base + ((j0 + j) * n1 + i0) * esize, rows, esize, shuffled + j * c1, n);
    uLong out = 0;
    int z = deflate_planes(shuffled, n, esize, level, by_plane, dst, cap - (sum ? 4 : 0), &out);
    if (z != 0) return z;
    if (sum) {
        uint32_t f = fletcher32(dst, (size_t)out);
        dst[out] = (unsigned char)(f & 0xff);
        dst[out + 1] = (unsigned char)((f >> 8) & 0xff);
        dst[out + 2] = (unsigned char)((f >> 16) & 0xff);
        dst[out + 3] = (unsigned char)((f >> 24) & 0xff);
        out += 4;
    }
    *len = (int64_t)out;
    return 0;
}
