/* psnr.c: PSNR of 8-bit pictures (see psnr.h). */
#include "psnr.h"

#include <math.h>

double psnr_sse(const uint8_t *a, const uint8_t *b, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)a[i] - b[i];
        s += d * d;
    }
    return s;
}

double psnr_db(double mse)
{
    return mse > 0 ? 10 * log10(255.0 * 255.0 / mse) : INFINITY;
}

double psnr_mse(double db)
{
    return isinf(db) ? 0 : 255.0 * 255.0 * pow(10, -db / 10);
}
