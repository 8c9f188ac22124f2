/*
 * imu.c - the e-puck 1.3's LSM330 (acc_gyro/e_lsm330.h) and the library's
 * accelerometer API over it (a_d/advance_ad_scan/e_acc.h), as the library
 * computes them on a 1.3; written from its documented behaviour, none of
 * its code.
 *
 * The accelerometer measures the specific force on the body (what an
 * accelerometer measures: at rest on the floor, 1 g up), in the LSM330's
 * units (16384 a g, the library's GRAVITY_LSM330; 16 bits, so it saturates
 * at 2 g): its X axis the robot's front, Y its left, Z up.  The inputs
 * (stub_set_acc, the scenario's accx/accy/accz) give it on the scale the
 * library keeps from the analog accelerometer of the e-puck before 1.3
 * (e_get_acc_filtered's: 2048 no acceleration, 768 a g), in the library's
 * frame: x the robot's left (the LSM330's Y), y its front (X), z up.
 * e_get_acc and the spherical readings are the library's computations over
 * what it last read (it reads the sensor at most every 64 ticks of the A/D
 * scan, 3.9 ms), with its calibration; e_display_angle lights the LED
 * toward the ground, as the library's.
 *
 * The gyroscope (the library sets it to 760 samples a second, a 30 Hz
 * low-pass, 250 degrees/s full scale: 8.75 mdps a unit) measures the
 * body's rate of turn: about z, the one its wheels' speeds give (with the
 * world's physics' correction in an Enki world, stub_set_turn_correction),
 * plus the rate a hand turns it at (stub_set_hand_rate, the scenario's
 * rotx/roty/rotz), filtered as the sensor does, sample by sample.
 *
 * No libm (as epuck_stub.c): the square root and atan2 are computed here,
 * the same on every C library.
 */
#include <stdlib.h>

#include "epuck_stub.h"
#include "library_sim.h"
#include "p30F6014A.h"
#include "motor_led/e_epuck_ports.h"
#include "acc_gyro/e_lsm330.h"
#include "a_d/advance_ad_scan/e_acc.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"

#define IMU_PI 3.14159265358979323846
#define COST() do { if (stub_cost_hook != NULL) stub_cost_hook(1L, STUB_CALL_CYCLES); } while (0)

/* ---- the square root and atan2, without libm ---------------------------------------------- */

static double imu_sqrt(double v)
{
    double g = 1.0, scale = 1.0;
    int k;
    if (v <= 0.0)
        return 0.0;
    while (v > 4.0) {           /* v in (1/4, 4]: Newton from 1 converges at once */
        v /= 4.0;
        scale *= 2.0;
    }
    while (v < 0.25) {
        v *= 4.0;
        scale /= 2.0;
    }
    for (k = 0; k < 8; k++)
        g = 0.5 * (g + v / g);
    return g * scale;
}

/* atan(z) for |z| <= 1: shifted by pi/6 above tan(pi/12), then its series */
static double imu_atan_unit(double z)
{
    static const double root3 = 1.7320508075688772935;
    double shift = 0.0, term, sum, z2;
    int k, negative = z < 0.0;
    if (negative)
        z = -z;
    if (z > 0.2679491924311227) {       /* tan(pi/12) */
        z = (z * root3 - 1.0) / (root3 + z);
        shift = IMU_PI / 6.0;
    }
    z2 = z * z;
    term = z;
    sum = z;
    for (k = 1; k < 14; k++) {
        term *= -z2;
        sum += term / (double)(2 * k + 1);
    }
    sum += shift;
    return negative ? -sum : sum;
}

static double imu_atan2(double y, double x)
{
    double a;
    if (x == 0.0 && y == 0.0)
        return 0.0;
    if (y < 0.0 ? -y <= (x < 0.0 ? -x : x) : y <= (x < 0.0 ? -x : x)) {
        a = imu_atan_unit(y / x);
        if (x < 0.0)
            a += y < 0.0 ? -IMU_PI : IMU_PI;
        return a;
    }
    a = IMU_PI / 2.0 - imu_atan_unit(x / y);
    return y < 0.0 ? a - IMU_PI : a;
}

/* ---- the accelerometer's inputs -------------------------------------------------------- */

static int acc_in[3] = { STUB_ACC_ZERO_G, STUB_ACC_ZERO_G, STUB_ACC_ZERO_G + STUB_ACC_ONE_G };

void stub_set_acc(int axis, int value)
{
    stub_input_set();
    if (axis >= 0 && axis < 3)
        acc_in[axis] = value;
}

/* the LSM330's reading of axis 0 X (front), 1 Y (left), 2 Z (up) */
static int lsm_acc(int axis)
{
    static const int from[3] = { 1, 0, 2 };     /* the analog scale's axis of each */
    long v = ((long)acc_in[from[axis]] - STUB_ACC_ZERO_G) * 64L / 3L;
    return v > 32767L ? 32767 : v < -32768L ? -32768 : (int)v;
}

void initAccAndGyro(void)
{
    COST();
}

int getXAxisAcc() { COST(); return lsm_acc(0); }
int getYAxisAcc() { COST(); return lsm_acc(1); }
int getZAxisAcc() { COST(); return lsm_acc(2); }

void getAllAxesAcc(signed int *x, signed int *y, signed int *z)
{
    COST();
    *x = lsm_acc(0);
    *y = lsm_acc(1);
    *z = lsm_acc(2);
}

/* little-endian pairs x, y, z as the sensor's registers */
static void raw_pairs(unsigned char *arr, int x, int y, int z)
{
    int v[3], i;
    v[0] = x;
    v[1] = y;
    v[2] = z;
    for (i = 0; i < 3; i++) {
        arr[2 * i] = (unsigned char)((unsigned)v[i] & 0xFFu);
        arr[2 * i + 1] = (unsigned char)(((unsigned)v[i] >> 8) & 0xFFu);
    }
}

void getAllAxesAccRaw(unsigned char *arr)
{
    COST();
    raw_pairs(arr, lsm_acc(0), lsm_acc(1), lsm_acc(2));
}

signed char getTemperature(void)
{
    COST();
    return 25;
}

/* ---- the gyroscope ------------------------------------------------------------------------ */

#define GYRO_DPS_PER_UNIT 0.00875

signed int gyroOffsetX, gyroOffsetY, gyroOffsetZ;

static double hand_dps[3];
static double correction_dps;
static double filtered[3];              /* the low-pass's state, degrees/s */
static unsigned long long samples;      /* the sensor's samples taken so far */

void stub_set_hand_rate(int axis, int dps)
{
    stub_input_set();
    if (axis >= 0 && axis < 3)
        hand_dps[axis] = dps;
}

void stub_set_turn_correction(double dps)
{
    correction_dps = dps;
}

/* the body's true rate about each axis now */
static double body_rate(int axis)
{
    double mm, axle, wheels = 0.0;
    if (axis == 2) {
        stub_geometry(&mm, &axle);
        wheels = (double)(stub_speed_right() - stub_speed_left()) * mm / axle * 180.0 / IMU_PI
                 + correction_dps;
    }
    return wheels + hand_dps[axis];
}

/* The samples due by now: each the first-order low-pass of the rate it
 * sees (a sample's weight 1 - exp(-2 pi 30 / 760)). */
static void gyro_sample(void)
{
    static const double alpha = 0.21965603259584843;
    unsigned long long due = stub_now_cycles() * 760ULL / STUB_FCY;
    int k;
    if (due > samples + 2000ULL)
        samples = due - 2000ULL;        /* after long: the filter has settled */
    for (; samples < due; samples++)
        for (k = 0; k < 3; k++)
            filtered[k] += alpha * (body_rate(k) - filtered[k]);
}

static int gyro_raw(int axis)
{
    double raw;
    gyro_sample();
    raw = filtered[axis] / GYRO_DPS_PER_UNIT;
    if (raw > 32767.0)
        return 32767;
    if (raw < -32768.0)
        return -32768;
    return (int)(raw < 0 ? raw - 0.5 : raw + 0.5);
}

int getXAxisGyro() { COST(); return gyro_raw(0) - gyroOffsetX; }
int getYAxisGyro() { COST(); return gyro_raw(1) - gyroOffsetY; }
int getZAxisGyro() { COST(); return gyro_raw(2) - gyroOffsetZ; }

void getAllAxesGyro(signed int *x, signed int *y, signed int *z)
{
    COST();
    *x = gyro_raw(0) - gyroOffsetX;
    *y = gyro_raw(1) - gyroOffsetY;
    *z = gyro_raw(2) - gyroOffsetZ;
}

void getAllAxesGyroRaw(unsigned char *arr)
{
    COST();
    raw_pairs(arr, gyro_raw(0), gyro_raw(1), gyro_raw(2));
}

/* as the library (declared without its parameter there): the mean of
 * numSamples readings becomes each axis's offset */
void calibrateGyroscope(int numSamples)
{
    long sum[3] = { 0, 0, 0 };
    int i;
    if (numSamples <= 0)
        return;
    for (i = 0; i < numSamples; i++) {
        COST();
        sum[0] += gyro_raw(0);
        sum[1] += gyro_raw(1);
        sum[2] += gyro_raw(2);
    }
    gyroOffsetX = (int)(sum[0] / numSamples);
    gyroOffsetY = (int)(sum[1] / numSamples);
    gyroOffsetZ = (int)(sum[2] / numSamples);
}

float rawToDps(int value)
{
    return (float)value * 0.00875f;
}

float rawToDpms(int value)
{
    return (float)value * 0.00000875f;
}

/* ---- the library's accelerometer API (a_d/advance_ad_scan/e_acc.h, on a 1.3) --------------- */

unsigned char isCalibratingFlag;
int centre_z = 2000;
int lastAccX, lastAccY, lastAccZ;
static int centre_x, centre_y;
static int angle_mem;
static int acc_x, acc_y, acc_z;
static float acceleration, orientation, inclination;
static unsigned long long read_at;      /* the A/D tick of the last reading */
static int ever_read;

/* The sensor is read again once 64 ticks of the A/D scan went by since the
 * last reading (the scan's counter: the library's updateAccI2CCounter). */
static void refresh(void)
{
    unsigned long long t = stub_ad_ticks();
    unsigned long long since = ever_read ? t - read_at : t;
    updateAccI2CCounter = (unsigned char)(since > 64ULL ? 64 : since);
    if (updateAccI2CCounter == 64) {
        lastAccX = lsm_acc(0);
        lastAccY = lsm_acc(1);
        lastAccZ = lsm_acc(2);
        read_at = t;
        ever_read = 1;
        updateAccI2CCounter = 0;
    }
}

/* the LSM330's 16 bits on the analog accelerometer's 12 (as the library:
 * a sixteenth less a sixty-fourth) */
static int twelve_bits(int v)
{
    return (v >> 4) - (v >> 6);
}

int e_get_acc(unsigned int captor)
{
    COST();
    refresh();
    switch (captor) {           /* x and y exchanged, as the library */
    case 0: return twelve_bits(lastAccY - centre_y);
    case 1: return twelve_bits(lastAccX - centre_x);
    case 2: return twelve_bits(lastAccZ - centre_z);
    default: return (int)ANGLE_ERROR;
    }
}

int e_get_acc_filtered(unsigned int captor, unsigned int filter_size)
{
    (void)filter_size;          /* the 1.3's sensor needs no filter: the library ignores it */
    COST();
    refresh();
    if (isCalibratingFlag) {
        switch (captor) {
        case 0: return lsm_acc(1);
        case 1: return lsm_acc(0);
        case 2: return lsm_acc(2);
        default: return (int)ANGLE_ERROR;
        }
    }
    switch (captor) {
    case 0: return twelve_bits(lastAccY) + 2048;
    case 1: return twelve_bits(lastAccX) + 2048;
    case 2: return twelve_bits(lastAccZ) + 2048;
    default: return (int)ANGLE_ERROR;
    }
}

static void calculate_raw(void)
{
    acc_x = e_get_acc(0);
    acc_y = e_get_acc(1);
    acc_z = e_get_acc(2);
}

static void calculate_spherical(void)
{
    float horizontal;
    calculate_raw();
    acceleration = (float)imu_sqrt((double)((long)acc_x * acc_x + (long)acc_y * acc_y
                                            + (long)acc_z * acc_z));
    horizontal = (float)imu_sqrt((double)((long)acc_x * acc_x + (long)acc_y * acc_y));
    inclination = 90.0f - (float)(imu_atan2((double)acc_z, (double)horizontal) * CST_RADIAN);
    if (inclination < 5 || inclination > 160)
        orientation = 0;
    else
        orientation = (float)(imu_atan2((double)acc_x, (double)acc_y) * CST_RADIAN) + 180.0f;
}

/* the library's calibration (its centres: x and y from the readings of
 * the other axis, as the library's) */
void e_acc_calibr(void)
{
    isCalibratingFlag = 1;
    centre_x = e_get_acc_filtered(ACCX_BUFFER, 50);
    centre_y = e_get_acc_filtered(ACCY_BUFFER, 50);
    centre_z = e_get_acc_filtered(ACCZ_BUFFER, 50) - GRAVITY_LSM330;
    isCalibratingFlag = 0;
}

TypeAccSpheric e_read_acc_spheric(void)
{
    TypeAccSpheric result;
    calculate_spherical();
    result.acceleration = acceleration;
    result.orientation = orientation;
    result.inclination = inclination;
    return result;
}

float e_read_inclination(void)
{
    calculate_spherical();
    return inclination;
}

float e_read_orientation(void)
{
    calculate_spherical();
    return orientation;
}

float e_read_acc(void)
{
    calculate_spherical();
    return acceleration;
}

TypeAccRaw e_read_acc_xyz(void)
{
    TypeAccRaw result;
    calculate_raw();
    result.acc_x = acc_x;
    result.acc_y = acc_y;
    result.acc_z = acc_z;
    return result;
}

int e_read_acc_x(void)
{
    calculate_raw();
    return acc_x;
}

int e_read_acc_y(void)
{
    calculate_raw();
    return acc_y;
}

int e_read_acc_z(void)
{
    calculate_raw();
    return acc_z;
}

/* The LED toward the ground: the orientation's octant, LED0 at 0 degrees
 * (the front down), LED7 at 45 ..., once it moved by more than 5 degrees
 * from where it was shown (the library's hysteresis, on the integer it
 * keeps). */
void e_display_angle(void)
{
    float angle = e_read_orientation();
    if (abs((int)((float)angle_mem - angle)) > 5) {     /* the library's abs() of a float */
        stub_outputs_mark();
        LED0 = LED1 = LED2 = LED3 = LED4 = LED5 = LED6 = LED7 = 0;
        if ((angle > 360.0f - 22.5f || angle <= 22.5f) && angle != (float)ANGLE_ERROR)
            LED0 = 1;
        else if (angle > 45.0f - 22.5f && angle <= 45.0f + 22.5f)
            LED7 = 1;
        else if (angle > 90.0f - 22.5f && angle <= 90.0f + 22.5f)
            LED6 = 1;
        else if (angle > 135.0f - 22.5f && angle <= 135.0f + 22.5f)
            LED5 = 1;
        else if (angle > 180.0f - 22.5f && angle <= 180.0f + 22.5f)
            LED4 = 1;
        else if (angle > 225.0f - 22.5f && angle <= 225.0f + 22.5f)
            LED3 = 1;
        else if (angle > 270.0f - 22.5f && angle <= 270.0f + 22.5f)
            LED2 = 1;
        else if (angle > 315.0f - 22.5f && angle <= 315.0f + 22.5f)
            LED1 = 1;
        angle_mem = (int)angle;
        stub_outputs_mark();
    }
}

void stub_imu_ms(long now_ms, long n)
{
    (void)now_ms;
    (void)n;
    gyro_sample();
}

void stub_imu_reset(void)
{
    int k;
    for (k = 0; k < 3; k++)
        filtered[k] = 0.0;
    gyroOffsetX = gyroOffsetY = gyroOffsetZ = 0;
    isCalibratingFlag = 0;
    centre_x = centre_y = 0;
    centre_z = 2000;
    angle_mem = 0;
    lastAccX = lastAccY = lastAccZ = 0;
    ever_read = 0;
}
