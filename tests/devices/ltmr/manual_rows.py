"""The LTMR register tables of manual 001 ("Register | CANopen Address |
Variable Type | ... | Note" rows, L2279-5098), one tuple per printed row:
register range, first and last CANopen address, the Variable Type cell, the
name cell and the note cell, as printed, typos included; the comment is the
manual line. Data for test_registers.py, copied, never computed.
"""

MANUAL_ROWS = (
    (0, 34, "2000:03", "2000:28", "(Not significant)", "", ""),  # L2288
    (35, 40, "2000:23", "2000:29", "Word[6]", "Expansion commercial reference DT_CommercialReference", "1"),  # L2292
    (41, 45, "2000:2A", "2000:2E", "Word[5]", "Expansion serial number", "1"),  # L2297
    (46, 46, "2000:2F", "2000:2F", "UInt", "Expansion ID code", "1"),  # L2302
    (47, 47, "2000:30", "2000:30", "UInt", "Expansion firmware version DT_FirmwareVersion", "1"),  # L2307
    (48, 48, "2000:31", "2000:31", "UInt", "Expansion compatibility code", "1"),  # L2312
    (49, 60, "2000:32", "2000:3D", "(Not significant)", "", ""),  # L2317
    (61, 61, "2000:3E", "2000:3E", "Ulnt", "Network port ID code", ""),  # L2321
    (62, 62, "2000:3F", "2000:3F", "Ulnt", "Network port firmware version DT_FirmwareVersion", ""),  # L2326
    (63, 63, "2000:40", "2000:40", "Ulnt", "Network port compatibility code", ""),  # L2331
    (64, 69, "2000:41", "2000:46", "Word[6]", "Controller commercial reference DT_CommercialReference", ""),  # L2336
    (70, 74, "2000:47", "2000:4B", "Word[5]", "Controller serial number", ""),  # L2341
    (75, 75, "2000:4C", "2000:4C", "Ulnt", "Controller ID code", ""),  # L2346
    (76, 76, "2000:4D", "2000:4D", "Ulnt", "Controller firmware version DT_FirmwareVersion", ""),  # L2351
    (77, 77, "2000:4E", "2000:4E", "Ulnt", "Controller compatibility code", ""),  # L2356
    (78, 78, "2000:4F", "2000:4F", "Ulnt", "Current scale ratio (0.1 %)", ""),  # L2361
    (79, 79, "2000:50", "2000:50", "Ulnt", "Current sensor max", ""),  # L2366
    (80, 80, "2000:51", "2000:51", "(Not significant)", "", ""),  # L2371
    (81, 81, "2000:52", "2000:52", "Ulnt", "Current range max (x 0.1 A)", ""),  # L2375
    (82, 94, "2000:53", "2000:58", "(Not significant)", "", ""),  # L2380
    (95, 95, "2000:60", "2000:60", "Ulnt", "Load CT ratio (x 0.1 A)", ""),  # L2384
    (
        96,
        96,
        "2000:61",
        "2000:61",
        "Ulnt",
        "Full load current max (maximum FLC range, FLC = Full Load Current) (x 0.1 A)",
        "",
    ),  # L2389
    (97, 99, "2000:62", "2000:64", "Ulnt", "(Forbidden)", ""),  # L2394
    (100, 101, "2001:01", "2001:02", "(Not significant)", "", ""),  # L2434
    (102, 102, "2001:03", "2001:03", "Ulnt", "Ground current trips count", ""),  # L2438
    (103, 103, "2001:04", "2001:04", "Ulnt", "Thermal overload trips count", ""),  # L2443
    (104, 104, "2001:05", "2001:05", "Ulnt", "Long start trips count", ""),  # L2448
    (105, 105, "2001:06", "2001:06", "Ulnt", "Jam trips count", ""),  # L2453
    (106, 106, "2001:07", "2001:07", "Ulnt", "Current phase imbalance trips count", ""),  # L2458
    (107, 107, "2001:08", "2001:08", "Ulnt", "Undercurrent trips count", ""),  # L2463
    (109, 109, "2001:0A", "2001:0A", "Ulnt", "HMI port trips count", ""),  # L2468
    (110, 110, "2001:0B", "2001:0B", "Ulnt", "Controller internal trips count", ""),  # L2473
    (111, 111, "2001:0C", "2001:0C", "Ulnt", "Internal port trips count", ""),  # L2478
    (112, 112, "2001:0D", "2001:0D", "(Not significant)", "", ""),  # L2483
    (113, 113, "2001:0E", "2001:0E", "Ulnt", "Network port config trips count", ""),  # L2487
    (114, 114, "2001:0F", "2001:0F", "Ulnt", "Network port trips count", ""),  # L2492
    (115, 115, "2001:10", "2001:10", "Ulnt", "Auto-resets count", ""),  # L2497
    (116, 116, "2001:11", "2001:11", "Ulnt", "Thermal overload alarms count", ""),  # L2502
    (117, 118, "2001:12", "2001:13", "UDlnt", "Motor starts count", ""),  # L2507
    (119, 120, "2001:14", "2001:15", "UDlnt", "Operating time (s)", ""),  # L2512
    (121, 121, "2001:16", "2001:16", "lnt", "Controller internal temperature max (°C)", ""),  # L2517
    (122, 122, "2001:17", "2001:17", "Ulnt", "Trips count", ""),  # L2529
    (123, 123, "2001:18", "2001:18", "Ulnt", "Alarms count", ""),  # L2534
    (124, 125, "2001:19", "2001:1A", "UDlnt", "Motor LO1 closings count", ""),  # L2539
    (126, 127, "2001:1B", "2001:1C", "UDlnt", "Motor LO2 closings count", ""),  # L2544
    (128, 128, "2001:1D", "2001:1D", "Ulnt", "Diagnostic trips count", ""),  # L2549
    (129, 129, "2001:1E", "2001:1E", "(Reserved)", "", ""),  # L2554
    (130, 130, "2001:1F", "2001:1F", "Ulnt", "Overcurrent trips count", ""),  # L2558
    (131, 131, "2001:20", "2001:20", "Ulnt", "Current phase loss trips count", ""),  # L2563
    (132, 132, "2001:21", "2001:21", "Ulnt", "Motor temperature sensor trips count", ""),  # L2568
    (133, 133, "2001:22", "2001:22", "Ulnt", "Voltage phase imbalance trips count", "1"),  # L2573
    (134, 134, "2001:23", "2001:23", "Ulnt", "Voltage phase loss trips count", "1"),  # L2578
    (135, 135, "2001:24", "2001:24", "Ulnt", "Wiring trips count", "1"),  # L2583
    (136, 136, "2001:25", "2001:25", "Ulnt", "Undervoltage trips count", "1"),  # L2588
    (137, 137, "2001:26", "2001:26", "Ulnt", "Overvoltage trips count", "1"),  # L2593
    (138, 138, "2001:27", "2001:27", "Ulnt", "Underpower trips count", "1"),  # L2598
    (139, 139, "2001:28", "2001:28", "Ulnt", "Overpower trips count", "1"),  # L2603
    (140, 140, "2001:29", "2001:29", "Ulnt", "Under power factor trips count", "1"),  # L2608
    (141, 141, "2001:2A", "2001:2A", "Ulnt", "Over power factor trips count", "1"),  # L2613
    (142, 142, "2001:2B", "2001:2B", "Ulnt", "Load sheddings count", "1"),  # L2618
    (143, 144, "2001:2C", "2001:2D", "UDlnt", "Active power consumption (kWh)", "1"),  # L2623
    (145, 146, "2001:2E", "2001:2F", "UDlnt", "Reactive power consumption (kVARh)", "1"),  # L2628
    (147, 147, "2001:30", "2001:30", "Ulnt", "Auto restart immediate count", ""),  # L2633
    (148, 148, "2001:31", "2001:31", "Ulnt", "Auto restart delayed count", ""),  # L2638
    (149, 149, "2001:32", "2001:32", "Ulnt", "Auto restart manual count", ""),  # L2643
    (150, 150, "2002:01", "2002:01", "Ulnt", "trip code n-0", ""),  # L2655
    (151, 151, "2002:02", "2002:02", "Ulnt", "Motor full load current ratio n-0 (% FLC max)", ""),  # L2660
    (152, 152, "2002:03", "2002:03", "Ulnt", "Thermal capacity level n-0 (% trip level)", ""),  # L2665
    (153, 153, "2002:04", "2002:04", "Ulnt", "Average current ratio n-0 (% FLC)", ""),  # L2670
    (154, 154, "2002:05", "2002:05", "Ulnt", "L1 current ratio n-0 (% FLC)", ""),  # L2675
    (155, 155, "2002:06", "2002:06", "Ulnt", "L2 current ratio n-0 (% FLC)", ""),  # L2680
    (156, 156, "2002:07", "2002:07", "Ulnt", "L3 current ratio n-0 (% FLC)", ""),  # L2685
    (157, 157, "2002:08", "2002:08", "Ulnt", "Ground current ratio n-0 (x 0.1 % FLC min)", ""),  # L2690
    (158, 158, "2002:09", "2002:09", "Ulnt", "Full load current max n-0 (x 0.1 A)", ""),  # L2695
    (159, 159, "2002:0A", "2002:0A", "Ulnt", "Current phase imbalance n-0 (%)", ""),  # L2700
    (160, 160, "2002:0B", "2002:0B", "Ulnt", "Frequency n-0 (x 0.1 Hz)", "2"),  # L2705
    (161, 161, "2002:0C", "2002:0C", "Ulnt", "Motor temperature sensor n-0 (x 0.1 Ω)", ""),  # L2710
    (162, 165, "2002:0D", "2002:10", "Word[4]", "Date and time n-0 DT_DateTime", ""),  # L2715
    (166, 166, "2002:11", "2002:11", "Ulnt", "Average voltage n-0 (V)", "1"),  # L2720
    (167, 167, "2002:12", "2002:12", "Ulnt", "L3-L1 voltage n-0 (V)", "1"),  # L2725
    (168, 168, "2002:13", "2002:13", "Ulnt", "L1-L2 voltage n-0 (V)", "1"),  # L2730
    (169, 169, "2002:14", "2002:14", "Ulnt", "L2-L3 voltage n-0 (V)", "1"),  # L2735
    (170, 170, "2002:15", "2002:15", "Ulnt", "Voltage phase imbalance n-0 (%)", "1"),  # L2740
    (171, 171, "2002:16", "2002:16", "Ulnt", "Active power n-0 (x 0.1 kWh)", "1"),  # L2745
    (172, 172, "2002:17", "2002:17", "Ulnt", "Power factor n-0 (x 0.01)", "1"),  # L2750
    (173, 179, "2002:18", "2002:1E", "(Not significant)", "", ""),  # L2755
    (180, 180, "2002:1F", "2002:1F", "Ulnt", "Trip code n-1", ""),  # L2766
    (181, 181, "2002:20", "2002:20", "Ulnt", "Motor full load current ratio n-1 (% FLC max)", ""),  # L2771
    (182, 182, "2002:21", "2002:21", "Ulnt", "Thermal capacity level n-1 (% trip level)", ""),  # L2776
    (183, 183, "2002:22", "2002:22", "Ulnt", "Average current ratio n-1 (% FLC)", ""),  # L2781
    (184, 184, "2002:23", "2002:23", "Ulnt", "L1 current ratio n-1 (% FLC)", ""),  # L2786
    (185, 185, "2002:24", "2002:24", "Ulnt", "L2 current ratio n-1 (% FLC)", ""),  # L2791
    (186, 186, "2002:25", "2002:25", "Ulnt", "L3 current ratio n-1 (% FLC)", ""),  # L2796
    (187, 187, "2002:26", "2002:26", "Ulnt", "Ground current ratio n-1 (x 0.1 % FLC min)", ""),  # L2801
    (188, 188, "2002:27", "2002:27", "Ulnt", "Full load current max n-1 (x 0.1 A)", ""),  # L2806
    (189, 189, "2002:28", "2002:28", "Ulnt", "Current phase imbalance n-1 (%)", ""),  # L2811
    (190, 190, "2002:29", "2002:29", "Ulnt", "Frequency n-1 (x 0.1 Hz)", "2"),  # L2816
    (191, 191, "2002:2A", "2002:2A", "Ulnt", "Motor temperature sensor n-1 (x 0.1 Ω)", ""),  # L2821
    (192, 195, "2002:2B", "2002:2E", "Word[4]", "Date and time n-1 DT_DateTime", ""),  # L2826
    (196, 196, "2002:2F", "2002:2F", "Ulnt", "Average voltage n-1 (V)", "1"),  # L2831
    (197, 197, "2002:30", "2002:30", "Ulnt", "L3-L1 voltage n-1 (V)", "1"),  # L2836
    (198, 198, "2002:31", "2002:31", "Ulnt", "L1-L2 voltage n-1 (V)", "1"),  # L2841
    (199, 199, "2002:32", "2002:32", "Ulnt", "L2-L3 voltage n-1 (V)", "1"),  # L2846
    (200, 200, "2002:33", "2002:33", "Ulnt", "Voltage phase imbalance n-1 (%)", "1"),  # L2851
    (201, 201, "2002:34", "2002:34", "Ulnt", "Active power n-1 (x 0.1 kWh)", "1"),  # L2856
    (202, 202, "2002:35", "2002:35", "Ulnt", "Power factor n-1 (x 0.01)", "1"),  # L2861
    (203, 209, "2002:36", "2002:3C", "(Not significant)", "", ""),  # L2866
    (210, 210, "2002:3D", "2002:3D", "Ulnt", "Trip code n-2", ""),  # L2877
    (211, 211, "2002:3E", "2002:3E", "Ulnt", "Motor full load current ratio n-2 (% FLC max)", ""),  # L2882
    (212, 212, "2002:3F", "2002:3F", "Ulnt", "Thermal capacity level n-2 (% trip level)", ""),  # L2887
    (213, 213, "2002:40", "2002:40", "Ulnt", "Average current ratio n-2 (% FLC)", ""),  # L2892
    (214, 214, "2002:41", "2002:41", "Ulnt", "L1 current ratio n-2 (% FLC)", ""),  # L2897
    (215, 215, "2002:42", "2002:42", "Ulnt", "L2 current ratio n-2 (% FLC)", ""),  # L2902
    (216, 216, "2002:43", "2002:43", "Ulnt", "L3 current ratio n-2 (% FLC)", ""),  # L2907
    (217, 217, "2002:44", "2002:44", "Ulnt", "Ground current ratio n-2 (x 0.1 % FLC min)", ""),  # L2912
    (218, 218, "2002:45", "2002:45", "Ulnt", "Full load current max n-2 (x 0.1 A)", ""),  # L2917
    (219, 219, "2002:46", "2002:46", "Ulnt", "Current phase imbalance n-2 (%)", ""),  # L2922
    (220, 220, "2002:47", "2002:47", "Ulnt", "Frequency n-2 (x 0.1 Hz)", "2"),  # L2927
    (221, 221, "2002:48", "2002:48", "Ulnt", "Motor temperature sensor n-2 (x 0.1 Ω)", ""),  # L2932
    (222, 225, "2002:49", "2002:4C", "Word[4]", "Date and time n-2 DT_DateTime", ""),  # L2937
    (226, 226, "2002:4D", "2002:4D", "Ulnt", "Average voltage n-2 (V)", "1"),  # L2942
    (227, 227, "2002:4E", "2002:4E", "Ulnt", "L3-L1 voltage n-2 (V)", "1"),  # L2947
    (228, 228, "2002:4F", "2002:4F", "Ulnt", "L1-L2 voltage n-2 (V)", "1"),  # L2952
    (229, 229, "2002:50", "2002:50", "Ulnt", "L2-L3 voltage n-2 (V)", "1"),  # L2957
    (230, 230, "2002:51", "2002:51", "Ulnt", "Voltage phase imbalance n-2 (%)", "1"),  # L2962
    (231, 231, "2002:52", "2002:52", "Ulnt", "Active power n-2 (x 0.1 kWh)", "1"),  # L2967
    (232, 232, "2002:53", "2002:53", "Ulnt", "Power factor n-2 (x 0.01)", "1"),  # L2972
    (233, 239, "2002:54", "2002:5A", "(Not significant)", "", ""),  # L2977
    (240, 240, "2002:5B", "2002:5B", "Ulnt", "Trip code n-3", ""),  # L2988
    (241, 241, "2002:5C", "2002:5C", "Ulnt", "Motor full load current ratio n-3 (% FLC max)", ""),  # L2993
    (242, 242, "2002:5D", "2002:5D", "Ulnt", "Thermal capacity level n-3 (% trip level)", ""),  # L2998
    (243, 243, "2002:5E", "2002:5E", "Ulnt", "Average current ratio n-3 (% FLC)", ""),  # L3003
    (244, 244, "2002:5F", "2002:5F", "Ulnt", "L1 current ratio n-3 (% FLC)", ""),  # L3008
    (245, 245, "2002:60", "2002:60", "Ulnt", "L2 current ratio n-3 (% FLC)", ""),  # L3013
    (246, 246, "2002:61", "2002:61", "Ulnt", "L3 current ratio n-3 (% FLC)", ""),  # L3018
    (247, 247, "2002:62", "2002:62", "Ulnt", "Ground current ratio n-3 (x 0.1 % FLC min)", ""),  # L3023
    (248, 248, "2002:63", "2002:63", "Ulnt", "Full load current max n-3 (0.1 A)", ""),  # L3028
    (249, 249, "2002:64", "2002:64", "Ulnt", "Current phase imbalance n-3 (%)", ""),  # L3033
    (250, 250, "2002:65", "2002:65", "Ulnt", "Frequency n-3 (x 0.1 Hz)", "2"),  # L3038
    (251, 251, "2002:66", "2002:66", "Ulnt", "Motor temperature sensor n-3 (x 0.1 Ω)", ""),  # L3043
    (252, 255, "2002:67", "2002:6A", "Word[4]", "Date and time n-3 DT_DateTime", ""),  # L3048
    (256, 256, "2002:6B", "2002:6B", "Ulnt", "Average voltage n-3 (V)", "1"),  # L3053
    (257, 257, "2002:6C", "2002:6C", "Ulnt", "L3-L1 voltage n-3 (V)", "1"),  # L3058
    (258, 258, "2002:6D", "2002:6D", "Ulnt", "L1-L2 voltage n-3 (V)", "1"),  # L3063
    (259, 259, "2002:6E", "2002:6E", "Ulnt", "L2-L3 voltage n-3 (V)", "1"),  # L3068
    (260, 260, "2002:6F", "2002:6F", "Ulnt", "Voltage phase imbalance n-3 (%)", "1"),  # L3073
    (261, 261, "2002:70", "2002:70", "Ulnt", "Active power n-3 (x 0.1 kWh)", "1"),  # L3078
    (262, 262, "2002:71", "2002:71", "Ulnt", "Power factor n-3 (x 0.01)", "1"),  # L3083
    (263, 269, "2002:72", "2002:78", "(Not significant)", "", ""),  # L3088
    (270, 270, "2002:79", "2002:79", "Ulnt", "Trip code n-4", ""),  # L3099
    (271, 271, "2002:7A", "2002:7A", "Ulnt", "Motor full load current ratio n-4 (% FLC max)", ""),  # L3104
    (272, 272, "2002:7B", "2002:7B", "Ulnt", "Thermal capacity level n-4 (% trip level)", ""),  # L3109
    (273, 273, "2002:7C", "2002:7C", "Ulnt", "Average current ratio n-4 (% FLC)", ""),  # L3114
    (274, 274, "2002:7D", "2002:7D", "Ulnt", "L1 current ratio n-4 (% FLC)", ""),  # L3119
    (275, 275, "2002:7E", "2002:7E", "Ulnt", "L2 current ratio n-4 (% FLC))", ""),  # L3124
    (276, 276, "2002:7F", "2002:7F", "Ulnt", "L3 current ratio n-4 (% FLC)", ""),  # L3129
    (277, 277, "2002:80", "2002:80", "Ulnt", "Ground current ratio n-4 (x 0.1 % FLC min)", ""),  # L3134
    (278, 278, "2002:81", "2002:81", "Ulnt", "Full load current max n-4 (x 0.1 A)", ""),  # L3139
    (279, 279, "2002:82", "2002:82", "Ulnt", "Current phase imbalance n-4 (%)", ""),  # L3144
    (280, 280, "2002:83", "2002:83", "Ulnt", "Frequency n-4 (x 0.1 Hz)", "2"),  # L3149
    (281, 281, "2002:84", "2002:84", "Ulnt", "Motor temperature sensor n-4 (x 0.1 Ω)", ""),  # L3154
    (282, 285, "2002:85", "2002:88", "Word[4]", "Date and time n-4 DT_DateTime", ""),  # L3159
    (286, 286, "2002:89", "2002:89", "Ulnt", "Average voltage n-4 (V)", "1"),  # L3164
    (287, 287, "2002:8A", "2002:8A", "Ulnt", "L3-L1 voltage n-4 (V)", "1"),  # L3169
    (288, 288, "2002:8B", "2002:8B", "Ulnt", "L1-L2 voltage n-4 (V)", "1"),  # L3174
    (289, 289, "2002:8C", "2002:8C", "Ulnt", "L2-L3 voltage n-4 (V)", "1"),  # L3179
    (290, 290, "2002:8D", "2002:8D", "Ulnt", "Voltage phase imbalance n-4 (x 1%)", "1"),  # L3184
    (291, 291, "2002:8E", "2002:8E", "Ulnt", "Active power n-4 (x 0.1 kWh)", "1"),  # L3189
    (292, 292, "2002:8F", "2002:8F", "Ulnt", "Power factor n-4 (x 0.01)", "1"),  # L3194
    (293, 299, "2002:90", "2002:96", "(Not significant)", "", ""),  # L3199
    (300, 301, "2003:01", "2003:02", "UDlnt", "Average current n-0 (x 0.01 A)", ""),  # L3210
    (302, 303, "2003:03", "2003:04", "UDlnt", "L1 current n-0 (x 0.01 A)", ""),  # L3215
    (304, 305, "2003:05", "2003:06", "UDlnt", "L2 current n-0 (x 0.01 A)", ""),  # L3220
    (306, 307, "2003:07", "2003:08", "UDlnt", "L3 current n-0 (x 0.01 A)", ""),  # L3225
    (308, 309, "2003:09", "2003:0A", "UDlnt", "Ground current n-0 (mA)", ""),  # L3230
    (310, 310, "2003:0B", "2003:0B", "Ulnt", "Motor temperature sensor degree n-0 (°C)", ""),  # L3235
    (330, 331, "2003:1F", "2003:20", "UDlnt", "Average current n-1 (x 0.01 A)", ""),  # L3247
    (332, 333, "2003:21", "2003:22", "UDlnt", "L1 current n-1 (x 0.01 A)", ""),  # L3252
    (334, 335, "2003:23", "2003:24", "UDlnt", "L2 current n-1 (x 0.01 A)", ""),  # L3257
    (336, 337, "2003:25", "2003:26", "UDlnt", "L3 current n-1 (x 0.01 A)", ""),  # L3262
    (338, 339, "2003:27", "2003:28", "UDlnt", "Ground current n-1 (mA)", ""),  # L3267
    (340, 340, "2003:29", "2003:29", "Ulnt", "Motor temperature sensor degree n-1 (°C)", ""),  # L3272
    (360, 361, "2003:3D", "2003:3E", "UDlnt", "Average current n-2 (x 0.01 A)", ""),  # L3284
    (362, 363, "2003:3F", "2003:40", "UDlnt", "L1 current n-2 (x 0.01 A)", ""),  # L3289
    (364, 365, "2003:41", "2003:42", "UDlnt", "L2 current n-2 (x 0.01 A)", ""),  # L3294
    (366, 367, "2003:43", "2003:44", "UDlnt", "L3 current n-2 (x 0.01 A)", ""),  # L3299
    (368, 369, "2003:45", "2003:46", "UDlnt", "Ground current n-2 (mA)", ""),  # L3304
    (370, 370, "2003:47", "2003:47", "Ulnt", "Motor temperature sensor degree n-2 (°C)", ""),  # L3309
    (390, 391, "2003:5B", "2003:5C", "UDlnt", "Average current n-3 (x 0.01 A)", ""),  # L3321
    (392, 393, "2003:5D", "2003:5E", "UDlnt", "L1 current n-3 (x 0.01 A)", ""),  # L3326
    (394, 395, "2003:5F", "2003:60", "UDlnt", "L2 current n-3 (x 0.01 A)", ""),  # L3331
    (396, 397, "2003:61", "2003:62", "UDlnt", "L3 current n-3 (x 0.01 A)", ""),  # L3336
    (398, 399, "2003:63", "2003:64", "UDlnt", "Ground current n-3 (mA)", ""),  # L3341
    (400, 400, "2003:65", "2003:65", "Ulnt", "Motor temperature sensor degree n-3 (°C)", ""),  # L3346
    (420, 421, "2003:79", "2003:7A", "UDlnt", "Average current n-4 (x 0.01 A)", ""),  # L3358
    (422, 423, "2003:7B9", "2003:7C", "UDlnt", "L1 current n-4 (x 0.01 A)", ""),  # L3363
    (424, 425, "2003:7D", "2003:7E", "UDlnt", "L2 current n-4 (x 0.01 A)", ""),  # L3368
    (426, 427, "2003:7F", "2003:80", "UDlnt", "L3 current n-4 (x 0.01 A)", ""),  # L3373
    (428, 429, "2003:81", "2003:82", "UDlnt", "Ground current n-4 (mA)", ""),  # L3378
    (430, 430, "2003:83", "2003:83", "Ulnt", "Motor temperature sensor degree n-4 (°C)", ""),  # L3383
    (450, 450, "2004:01", "2004:01", "Ulnt", "Minimum wait time (s)", ""),  # L3412
    (
        451,
        451,
        "2004:02",
        "2004:02",
        "Ulnt",
        "Trip code (code of the last trip, or of the trip that takes priority) DT_FaultCode",
        "",
    ),  # L3417
    (452, 452, "2004:03", "2004:03", "Word", "Trip register 1", ""),  # L3423
    (453, 453, "2004:04", "2004:04", "Word", "Trip register 2", ""),  # L3459
    (454, 454, "2004:05", "2004:05", "Word", "Trip register 3", ""),  # L3507
    (455, 455, "2004:06", "2004:06", "Word", "System status register 1", ""),  # L3516
    (456, 456, "2004:07", "2004:07", "Word", "System status register 2", ""),  # L3544
    (457, 457, "2004:08", "2004:08", "Word", "Logic inputs status", ""),  # L3572
    (458, 458, "2004:09", "2004:09", "Word", "Logic outputs status", ""),  # L3618
    (459, 459, "2004:0A", "2004:0A", "Word", "I/O status", ""),  # L3645
    (460, 460, "2004:0B", "2004:0B", "UInt", "Alarm code DT_WarningCode", ""),  # L3682
    (461, 461, "2004:0C", "2004:0C", "Word", "Alarm register 1", ""),  # L3688
    (462, 462, "2004:0D", "2004:0D", "Word", "Alarm register 2", ""),  # L3718
    (463, 463, "2004:0E", "2004:0E", "Word", "Alarm register 3", ""),  # L3764
    (464, 464, "2004:0F", "2004:0F", "", "Motor temperature sensor degree (°C)", ""),  # L3773, type cell empty (A17)
    (465, 465, "2004:10", "2004:10", "UInt", "Thermal capacity level (% trip level)", ""),  # L3777
    (466, 466, "2004:11", "2004:11", "UInt", "Average current ratio (% FLC)", ""),  # L3782
    (467, 467, "2004:12", "2004:12", "UInt", "L1 current ratio (% FLC)", ""),  # L3787
    (468, 468, "2004:13", "2004:13", "UInt", "L2 current ratio (% FLC)", ""),  # L3792
    (469, 469, "2004:14", "2004:14", "UInt", "L3 current ratio (% FLC)", ""),  # L3797
    (470, 470, "2004:15", "2004:15", "UInt", "Ground current ratio (x 0.1 % FLC min)", ""),  # L3802
    (471, 471, "2004:16", "2004:16", "UInt", "Current phase imbalance (%)", ""),  # L3807
    (472, 472, "2004:17", "2004:17", "Int", "Controller internal temperature (°C)", ""),  # L3812
    (473, 473, "2004:18", "2004:18", "UInt", "Controller config checksum", ""),  # L3817
    (474, 474, "2004:19", "2004:19", "UInt", "Frequency (x 0.01 Hz)", "2"),  # L3822
    (475, 475, "2004:1A", "2004:1A", "UInt", "Motor temperature sensor (x 0.1 Ω)", ""),  # L3827
    (476, 476, "2004:1B", "2004:1B", "UInt", "Average voltage (V)", "1"),  # L3832
    (477, 477, "2004:1C", "2004:1C", "UInt", "L3-L1 voltage (V)", "1"),  # L3837
    (478, 478, "2004:1D", "2004:1D", "UInt", "L1-L2 voltage (V)", "1"),  # L3842
    (479, 479, "2004:1E", "2004:1E", "UInt", "L2-L3 voltage (V)", "1"),  # L3847
    (480, 480, "2004:1F", "2004:1F", "UInt", "Voltage phase imbalance (%)", "1"),  # L3852
    (481, 481, "2004:20", "2004:20", "UInt", "Power factor (x 0.01)", "1"),  # L3857
    (482, 482, "2004:21", "2004:21", "UInt", "Active power (x 0.1 kW)", "1"),  # L3862
    (483, 483, "2004:22", "2004:22", "UInt", "Reactive power (x 0.1 kVAR)", "1"),  # L3867
    (484, 484, "2004:23", "2004:23", "Word", "Auto restart status register", ""),  # L3872
    (485, 489, "2004:24", "2004:28", "(Not significant)", "", ""),  # L3889
    (490, 490, "2004:29", "2004:29", "Word", "Network port status", ""),  # L3893
    (491, 491, "2004:2A", "2004:2A", "UInt", "network port baud rate DT_ExtBaudRate", ""),  # L3910
    (492, 492, "2004:2B", "2004:2B", "(Not significant)", "", ""),  # L3915
    (493, 493, "2004:2C", "2004:2C", "UInt", "Network port parity DT_ExtParity", ""),  # L3919
    (494, 499, "2004:2D", "2004:32", "(Not significant)", "", ""),  # L3924
    (500, 501, "2004:33", "2004:34", "UDInt", "Average current (x 0.01 A)", ""),  # L3928
    (502, 503, "2004:35", "2004:36", "UDInt", "L1 current (x 0.01 A)", ""),  # L3933
    (504, 505, "2004:37", "2004:38", "UDInt", "L2 current (x 0.01 A)", ""),  # L3938
    (506, 507, "2004:39", "2004:3A", "UDInt", "L3 current (x 0.01 A)", ""),  # L3943
    (508, 509, "2004:3B", "2004:3C", "UDInt", "Ground current (mA)", ""),  # L3948
    (510, 510, "2004:3D", "2004:3D", "UInt", "Controller port ID", ""),  # L3953
    (511, 511, "2004:3E", "2004:3E", "UInt", "Time to trip (x 1 s)", ""),  # L3958
    (512, 512, "2004:3F", "2004:3F", "UInt", "Motor last start current ratio (% FLC)", ""),  # L3963
    (513, 513, "2004:40", "2004:40", "UInt", "Motor last start duration (s)", ""),  # L3968
    (514, 514, "2004:41", "2004:41", "UInt", "Motor starts per hour count", ""),  # L3973
    (515, 515, "2004:42", "2004:42", "Word", "Phase imbalances register", ""),  # L3978
    (516, 523, "2004:43", "2004:4A", "UInt", "(Reserved)", "1"),  # L4001
    (524, 539, "2004:4B", "2004:5A", "UInt", "(Forbidden)", "1"),  # L4006
    (
        540,
        540,
        "2005:01",
        "2005:01",
        "UInt",
        "Motor operating mode: 2 = 2-wire overload 3 = 3-wire overload 4 = 2-wire independent 5 = 3-wire "
        "independent 6 = 2-wire reverser 7 = 3-wire reverser 8 = 2-wire 2-step 9 = 3-wire 2-step 10 = 2-wire "
        "2-speed 11 = 3-wire 2-speed 256-511 = Custom logic program (0-255)",
        "B",
    ),  # L4030
    (541, 541, "2005:02", "2005:02", "UInt", "Motor transition timeout (s)", ""),  # L4035
    (542, 544, "2005:03", "2005:05", "(Reserved)", "", ""),  # L4040
    (545, 545, "2005:06", "2005:06", "Word", "Controller AC inputs setting register", ""),  # L4044
    (546, 546, "2005:07", "2005:07", "UInt", "Thermal overload setting", "B"),  # L4053
    (547, 547, "2005:08", "2005:08", "UInt", "Thermal overload trip definite timeout (s)", ""),  # L4064
    (548, 548, "2005:09", "2005:09", "(Reserved)", "", ""),  # L4069
    (549, 549, "2005:0A", "2005:0A", "UInt", "Motor temperature sensor trip threshold (x 0.1 Ω)", ""),  # L4073
    (550, 550, "2005:0B", "2005:0B", "UInt", "Motor temperature sensor alarm threshold (x 0.1 Ω)", ""),  # L4078
    (551, 551, "2005:0C", "2005:0C", "Ulnt", "Motor temperature sensor trip threshold degree (°C)", ""),  # L4083
    (552, 552, "2005:0D", "2005:0D", "Ulnt", "Motor temperature sensor alarm threshold degree (°C)", ""),  # L4088
    (553, 553, "2005:0E", "2005:0E", "UInt", "Rapid cycle lockout timeout (s)", ""),  # L4093
    (554, 554, "2005:0F", "2005:0F", "UInt", "(Reserved)", ""),  # L4098
    (555, 555, "2005:10", "2005:10", "UInt", "Current phase loss timeout (x 0.1 s)", ""),  # L4103
    (556, 556, "2005:11", "2005:11", "UInt", "Overcurrent trip timeout (s)", ""),  # L4108
    (557, 557, "2005:12", "2005:12", "UInt", "Overcurrent trip threshold (% FLC)", ""),  # L4113
    (558, 558, "2005:13", "2005:13", "UInt", "Overcurrent alarm threshold (% FLC)", ""),  # L4118
    (559, 559, "2005:14", "2005:14", "Word", "Ground current trip configuration", "B"),  # L4123
    (560, 560, "2005:15", "2005:15", "UInt", "Ground current sensor client", ""),  # L4132
    (561, 561, "2005:16", "2005:16", "UInt", "Ground current sensor server", ""),  # L4137
    (562, 562, "2005:17", "2005:17", "UInt", "External ground current trip timeout (x 0.01 s)", ""),  # L4142
    (563, 563, "2005:18", "2005:18", "UInt", "External ground current trip threshold (x 0.01 A)", ""),  # L4147
    (564, 564, "2005:19", "2005:19", "UInt", "External ground current alarm threshold (x 0.01 A)", ""),  # L4152
    (565, 565, "2005:1A", "2005:1A", "UInt", "Motor nominal voltage (V)", "1"),  # L4157
    (566, 566, "2005:1B", "2005:1B", "UInt", "Voltage phase imbalance trip timeout starting (x 0.1 s)", "1"),  # L4162
    (567, 567, "2005:1C", "2005:1C", "UInt", "Voltage phase imbalance trip timeout running (x 0.1 s)", "1"),  # L4167
    (568, 568, "2005:1D", "2005:1D", "UInt", "Voltage phase imbalance trip threshold (% imb)", "1"),  # L4172
    (569, 569, "2005:1E", "2005:1E", "UInt", "Voltage phase imbalance alarm threshold (% imb)", "1"),  # L4177
    (570, 570, "2005:1F", "2005:1F", "UInt", "Overvoltage trip timeout (x 0.1 s)", "1"),  # L4182
    (571, 571, "2005:20", "2005:20", "UInt", "Overvoltage trip threshold (x Vnom)", "1"),  # L4187
    (572, 572, "2005:21", "2005:21", "UInt", "Overvoltage alarm threshold (x Vnom)", "1"),  # L4192
    (573, 573, "2005:22", "2005:22", "UInt", "Undervoltage trip timeout (x 0.1 s)", "1"),  # L4197
    (574, 574, "2005:23", "2005:23", "UInt", "Undervoltage trip threshold (x Vnom)", "1"),  # L4202
    (575, 575, "2005:24", "2005:24", "UInt", "Undervoltage alarm threshold (x Vnom)", "1"),  # L4207
    (576, 576, "2005:25", "2005:25", "UInt", "Voltage phase loss trip timeout (x 0.1 s)", "1"),  # L4212
    (577, 577, "2005:26", "2005:26", "Word", "Voltage dip setting", "1"),  # L4217
    (578, 578, "2005:27", "2005:27", "UInt", "Load shedding timeout (s)", "1"),  # L4228
    (579, 579, "2005:28", "2005:28", "UInt", "Voltage dip threshold (% Vnom)", "1"),  # L4233
    (580, 580, "2005:29", "2005:29", "UInt", "Voltage dip restart timeout (s)", "1"),  # L4238
    (581, 581, "2005:2A", "2005:2A", "UInt", "Voltage dip restart threshold (% Vnom)", "1"),  # L4243
    (582, 582, "2005:2B", "2005:2B", "UInt", "Auto restart immediate timeout (x 0.1 s)", ""),  # L4248
    (583, 583, "2005:2C", "2005:2C", "UInt", "Motor nominal power (x 0.1 kW)", "1"),  # L4253
    (584, 584, "2005:2D", "2005:2D", "UInt", "Overpower trip timeout (s)", "1"),  # L4258
    (585, 585, "2005:2E", "2005:2E", "UInt", "Overpower trip threshold (% Pnom)", "1"),  # L4263
    (586, 586, "2005:2F", "2005:2F", "UInt", "Overpower alarm threshold (% Pnom)", "1"),  # L4268
    (587, 587, "2005:30", "2005:30", "UInt", "Underpower trip timeout (s)", "1"),  # L4273
    (588, 588, "2005:31", "2005:31", "UInt", "Underpower trip threshold (% Pnom)", "1"),  # L4278
    (589, 589, "2005:32", "2005:32", "UInt", "Underpower alarm threshold (% Pnom)", "1"),  # L4283
    (590, 590, "2005:33", "2005:33", "UInt", "Under power factor trip timeout (x 0.1 s)", "1"),  # L4288
    (591, 591, "2005:34", "2005:34", "UInt", "Under power factor trip threshold (x 0.01 PF)", "1"),  # L4293
    (592, 592, "2005:35", "2005:35", "UInt", "Under power factor alarm threshold (x 0.01 PF)", "1"),  # L4298
    (593, 593, "2005:36", "2005:36", "UInt", "Over power factor trip timeout (x 0.1 s)", "1"),  # L4303
    (594, 594, "2005:37", "2005:37", "UInt", "Over power factor trip threshold (x 0.01 PF)", "1"),  # L4308
    (595, 595, "2005:38", "2005:38", "UInt", "Over power factor alarm threshold (x 0.01 PF)", "1"),  # L4313
    (596, 596, "2005:39", "2005:39", "", "Auto restart delayed timeout (s)", ""),  # L4318, type cell empty (A17)
    (597, 599, "2005:3A", "2005:3C", "(Reserved)", "", ""),  # L4322
    (600, 600, "2006:01", "2006:01", "(Not significant)", "", ""),  # L4326
    (601, 601, "2006:02", "2006:02", "Word", "General configuration register 1", ""),  # L4330
    (602, 602, "2006:03", "2006:03", "Word", "General configuration register 2", ""),  # L4358
    (603, 603, "2006:04", "2006:04", "Ulnt", "HMI port address setting", ""),  # L4378
    (604, 604, "2006:05", "2006:05", "Ulnt", "HMI port baud rate setting (Baud)", ""),  # L4383
    (605, 605, "2006:06", "2006:06", "(Reserved)", "", ""),  # L4388
    (606, 606, "2006:07", "2006:07", "Ulnt", "Motor trip class (s)", ""),  # L4392
    (607, 607, "2006:08", "2006:08", "(Reserved)", "", ""),  # L4397
    (608, 608, "2006:09", "2006:09", "Ulnt", "Thermal overload trip reset threshold (% trip level)", ""),  # L4401
    (609, 609, "2006:0A", "2006:0A", "Ulnt", "Thermal overload alarm threshold (% trip level)", ""),  # L4406
    (610, 610, "2006:0B", "2006:0B", "UInt", "Internal ground current trip timeout (x 0.1 s)", ""),  # L4411
    (611, 611, "2006:0C", "2006:0C", "UInt", "Internal ground current trip threshold (% FLCmin)", ""),  # L4416
    (612, 612, "2006:0D", "2006:0D", "UInt", "Internal ground current alarm threshold (% FLCmin)", ""),  # L4421
    (613, 613, "2006:0E", "2006:0E", "UInt", "Current phase imbalance trip timeout starting (x 0.1 s)", ""),  # L4426
    (614, 614, "2006:0F", "2006:0F", "UInt", "Current phase imbalance trip timeout running (x 0.1 s)", ""),  # L4431
    (615, 615, "2006:10", "2006:10", "UInt", "Current phase imbalance trip threshold (% imb)", ""),  # L4436
    (616, 616, "2006:11", "2006:11", "UInt", "Current phase imbalance alarm threshold (% imb)", ""),  # L4441
    (617, 617, "2006:12", "2006:12", "UInt", "Jam trip timeout (s)", ""),  # L4446
    (618, 618, "2006:13", "2006:13", "UInt", "Jam trip threshold (% FLC)", ""),  # L4451
    (619, 619, "2006:14", "2006:14", "UInt", "Jam alarm threshold (% FLC)", ""),  # L4456
    (620, 620, "2006:15", "2006:15", "UInt", "Undercurrent trip timeout (s)", ""),  # L4461
    (621, 621, "2006:16", "2006:16", "UInt", "Undercurrent trip threshold (% FLC)", ""),  # L4466
    (622, 622, "2006:17", "2006:17", "UInt", "Undercurrent alarm threshold (% FLC)", ""),  # L4471
    (623, 623, "2006:18", "2006:18", "UInt", "Long start trip timeout (s)", ""),  # L4476
    (624, 624, "2006:19", "2006:19", "UInt", "Long start trip threshold (% FLC)", ""),  # L4481
    (625, 625, "2006:1A", "2006:1A", "(Reserved)", "", ""),  # L4486
    (626, 626, "2006:1B", "2006:1B", "UInt", "HMI display contrast setting", ""),  # L4490
    (627, 627, "2006:1C", "2006:1C", "UInt", "Contactor rating (0.1 A)", ""),  # L4499
    (628, 628, "2006:1D", "2006:1D", "UInt", "Load CT client", "B"),  # L4504
    (629, 629, "2006:1E", "2006:1E", "UInt", "Load CT server", "B"),  # L4509
    (630, 630, "2006:1F", "2006:1F", "UInt", "Load CT multiple passes (passes)", "B"),  # L4514
    (631, 631, "2006:20", "2006:20", "Word", "Trip enable register 1", ""),  # L4519
    (632, 632, "2006:21", "2006:21", "Word", "Alarm enable register 1", ""),  # L4548
    (633, 633, "2006:22", "2006:22", "Word", "Trip enable register 2", ""),  # L4579
    (634, 634, "2006:23", "2006:23", "Word", "Alarm enable register 2", ""),  # L4625
    (635, 636, "2006:24", "2006:25", "(Reserved)", "", ""),  # L4671
    (637, 637, "2006:26", "2006:26", "UInt", "Auto-reset attempts group 1 setting", ""),  # L4675
    (638, 638, "2006:27", "2006:27", "UInt", "Auto-reset group 1 timeout", ""),  # L4680
    (639, 639, "2006:28", "2006:28", "UInt", "Auto-reset attempts group 2 setting", ""),  # L4685
    (640, 640, "2006:29", "2006:29", "UInt", "Auto-reset group 2 timeout", ""),  # L4690
    (641, 641, "2006:2A", "2006:2A", "UInt", "Auto-reset attempts group 3 setting", ""),  # L4695
    (642, 642, "2006:2B", "2006:2B", "UInt", "Auto-reset group 3 timeout", ""),  # L4700
    (643, 643, "2006:2C", "2006:2C", "UInt", "Motor step 1 to 2 timeout", ""),  # L4705
    (644, 644, "2006:2D", "2006:2D", "UInt", "Motor step 1 to 2 threshold", ""),  # L4710
    (645, 645, "2006:2E", "2006:2E", "UInt", "HMI port fallback setting DT_OutputFallbackStrategy", ""),  # L4715
    (646, 649, "2006:2F", "2006:32", "(Reserved)", "", ""),  # L4720
    (650, 650, "2007:01", "2007:01", "Word", "HMI language setting register:", ""),  # L4724
    (651, 651, "2007:02", "2007:02", "Word", "HMI display items register 1", ""),  # L4733
    (652, 652, "2007:03", "2007:03", "Ulnt", "Motor full load current ratio, FLC1 (% FLCmax)", ""),  # L4770
    (653, 653, "2007:04", "2007:04", "Ulnt", "Motor high speed full load current ratio, FLC2 (% FLCmax)", ""),  # L4775
    (654, 654, "2007:05", "2007:05", "Word", "HMI display items register 2", ""),  # L4780
    (655, 658, "2007:06", "2007:09", "Word[4]", "Date and time setting DT_DateTime", ""),  # L4828
    (659, 659, "2007:0A", "2007:0A", "Word", "HMI display items register 3", ""),  # L4833
    (660, 681, "2007:0B", "2007:20", "(Reserved)", "", ""),  # L4842
    (682, 682, "2007:21", "2007:21", "Ulnt", "Network port fallback setting DT_OutputFallbackStrategy", ""),  # L4846
    (683, 683, "2007:22", "2007:22", "Word", "Control setting register", ""),  # L4851
    (684, 692, "2007:23", "2007:2D", "Word", "(Reserved", ""),  # L4880
    (695, 695, "2007:2E", "2007:2E", "Ulnt", "Network port baud rate setting (Baud) DT_ExtBaudRate", ""),  # L4885
    (696, 696, "2007:2F", "2007:2F", "Ulnt", "Network port address setting", ""),  # L4890
    (697, 699, "2007:30", "2007:32", "Word", "(Not significant)", ""),  # L4895
    (
        700,
        700,
        "2008:01",
        "2008:01",
        "Word",
        "Register available to remotely write commands that can be processed in a specific custom logic",
        "",
    ),  # L4908
    (701, 703, "2008:02", "2008:04", "(Reserved)", "", ""),  # L4913
    (704, 704, "2008:05", "2008:05", "Word", "Control register 1", ""),  # L4917
    (705, 705, "2008:06", "2008:06", "Word", "Control register 2", ""),  # L4938
    (706, 709, "2008:07", "2008:0A", "(Reserved)", "", ""),  # L4956
    (707, 799, "2008:0B", "2008:64", "(Forbidden)", "", ""),  # L4960
    (1200, 1200, "200D:01", "200D:01", "Word", "Custom logic status register", ""),  # L4972
    (1201, 1201, "200D:02", "200D:02", "Word", "Custom logic version", ""),  # L5009
    (1202, 1202, "200D:03", "200D:03", "Word", "Custom logic memory space", ""),  # L5014
    (1203, 1203, "200D:04", "200D:04", "Word", "Custom logic memory used", ""),  # L5019
    (1204, 1204, "200D:05", "200D:05", "Word", "Custom logic temporary space", ""),  # L5024
    (1205, 1205, "200D:06", "200D:06", "Word", "Custom logic non volatile space", ""),  # L5029
    (1206, 1249, "200D:07", "200D:32", "(Reserved)", "", ""),  # L5034
    (1250, 1250, "200D:33", "200D:33", "Word", "Custom logic setting register 1", ""),  # L5043
    (1251, 1269, "200D:34", "200D:46", "(Reserved)", "", ""),  # L5054
    (1270, 1270, "200D:47", "200D:47", "Word", "Custom logic command register 1", ""),  # L5058
    (1271, 1279, "200D:48", "200D:50", "(Reserved)", "", ""),  # L5067
    (1280, 1280, "200D:51", "200D:51", "Word", "Custom logic monitoring register 1", ""),  # L5076
    (1281, 1300, "200D:52", "200D:65", "(Reserved)", "", ""),  # L5087
    (1301, 1399, "200D:66", "200D:C8", "Word[99]", "General purpose registers for logic functions", ""),  # L5096
)
