"""Wall time of a 1-hour, 100 Hz FMPy run of the FMU (360,000 communication steps): python fmpy_one_hour.py RinsImu.fmu"""
import time, fmpy, sys
t0 = time.perf_counter()
r = fmpy.simulate_fmu(sys.argv[1], stop_time=3600.0, output_interval=0.01, output=["imu.dtheta_rad[0]", "imu.dtheta_rad[1]", "imu.dtheta_rad[2]", "imu.dv_mps[0]", "imu.dv_mps[1]", "imu.dv_mps[2]"] if "3" not in sys.argv[1] else ["imu.dtheta_rad", "imu.dv_mps"])
print(sys.argv[1], len(r), "rows", round(time.perf_counter() - t0, 2), "s")
