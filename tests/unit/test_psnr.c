/* test_psnr.c: the one PSNR formula (psnr.h) against values worked out by hand. */
#include <math.h>

#include "psnr.h"
#include "test.h"

TEST(psnr_of_hand_values)
{
    CHECK(isinf(psnr_db(0)) && psnr_db(0) > 0); /* identical pictures */
    CHECK_NEAR(psnr_db(255.0 * 255.0), 0, 1e-12); /* every channel off by the full range */
    CHECK_NEAR(psnr_db(255.0 * 255.0 / 100), 20, 1e-12);
    CHECK_NEAR(psnr_db(36), 32.5678, 1e-4); /* RMS 6 levels: the minification sweep's bar */
    CHECK(psnr_mse(INFINITY) == 0);
    CHECK_NEAR(psnr_mse(psnr_db(36)), 36, 1e-9);
}

TEST(psnr_sse_sums_squared_byte_differences)
{
    const uint8_t a[4] = {0, 255, 10, 7}, b[4] = {255, 0, 13, 7};
    CHECK(psnr_sse(a, b, 4) == 255.0 * 255 * 2 + 9);
    CHECK(psnr_sse(a, a, 4) == 0);
    CHECK(psnr_sse(a, b, 0) == 0);
}
