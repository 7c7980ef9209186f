/* zlib for fracas_vtk: compress one array in VTK's blocks (vtkZLibDataCompressor
 * layout), each block a complete zlib stream. One deflate state serves every
 * block (deflateReset), and the strategy can be Z_RLE (run-length matches only:
 * two to three times faster than the default on simulation data, files about 15 %
 * bigger).
 *
 * fracas_zlib_blocks(src, n, block, level, rle, dst, cap, sizes): the n bytes of src
 * in ceil(n / block) blocks; the compressed blocks go one after another into dst
 * (cap bytes), their sizes into sizes[]. Returns the total compressed size, or -1
 * (dst too small, or a zlib error). fracas_zlib_bound(block): the most one block can
 * take. */
#include <zlib.h>

long fracas_zlib_bound(long block)
{
    return (long)compressBound((uLong)block);
}

long fracas_zlib_blocks(const unsigned char *src, long n, long block, int level, int rle,
                        unsigned char *dst, long cap, long long *sizes)
{
    z_stream s;
    long done = 0, total = 0, k = 0;
    s.zalloc = Z_NULL;
    s.zfree = Z_NULL;
    s.opaque = Z_NULL;
    if (deflateInit2(&s, level, Z_DEFLATED, 15, 8, rle ? Z_RLE : Z_DEFAULT_STRATEGY) != Z_OK) return -1;
    while (done < n) {
        long len = n - done < block ? n - done : block;
        if (deflateReset(&s) != Z_OK) break;
        s.next_in = (Bytef *)(src + done);
        s.avail_in = (uInt)len;
        s.next_out = dst + total;
        s.avail_out = (uInt)(cap - total);
        if (deflate(&s, Z_FINISH) != Z_STREAM_END) break;
        sizes[k++] = (long long)s.total_out;
        total += (long)s.total_out;
        done += len;
    }
    deflateEnd(&s);
    return done == n ? total : -1;
}
