# dpend sweep --device (docs/gpu.md): the values of --device and
# --gpu-repack, --device gpu without the library (none in the scratch directory,
# none next to the debug binary, $DPEND_GPU_LIB unset by CI) and for what the GPU
# does not compute (indicators, the Lyapunov exponent, parameter axes, N links, the
# elastic pendulum): one line naming device, exit 2, before any work. --device auto
# without a GPU computes on the CPU.

printf '&sweep\n  device = %s\n/\n' "'xpu'" > "$FIXTURES/gpu_bad_device.nml"
printf '&sweep\n  device = %s\n  n1 = 4, n2 = 4\n/\n&integration t_end = 1.0 /\n' "'auto'" \
  > "$FIXTURES/gpu_auto.nml"
G=(sweep --n 4 --t-end 1 --quiet --output g.h5)
# ---- values
refuse  gpu-device-token        device      -- "${G[@]}" --device xpu
refuse  gpu-device-empty        device      -- "${G[@]}" --device ''
refuse  gpu-device-prefix       device      -- "${G[@]}" --device gpu0
refuse  gpu-device-nml          device      -- "${G[@]}" --config gpu_bad_device.nml
refuse  gpu-device-missing      device      -- "${G[@]}" --device
refuse  gpu-repack-negative     gpu_repack  -- "${G[@]}" --gpu-repack -1
refuse  gpu-repack-text         gpu-repack  -- "${G[@]}" --gpu-repack many
refuse  gpu-repack-fraction     gpu-repack  -- "${G[@]}" --gpu-repack 2.5
# ---- the GPU refused: no library here, or a map it does not compute
refuse  gpu-no-library          device      -- "${G[@]}" --device gpu
refuse  gpu-lyapunov            device      -- "${G[@]}" --device gpu --lyapunov
refuse  gpu-indicator-megno     device      -- "${G[@]}" --device gpu --indicator megno
refuse  gpu-indicator-lambda1   device      -- "${G[@]}" --device gpu --indicator lambda1
refuse  gpu-param-axis          device      -- "${G[@]}" --device gpu --axis1 m2/m1 --min1 0.5 --max1 2
refuse  gpu-three-links         device      -- "${G[@]}" --device gpu --links 3 --block 4
refuse  gpu-elastic             device      -- sweep --model elastic --q 1.2,-1.0 --n 3 --t-end 1 --indicator megno --axis1 r --min1 0.8 --max1 1.6 --axis2 phi --quiet --output e.h5 --device gpu
# ---- auto without a GPU: the CPU
succeed gpu-auto-cpu            -- "${G[@]}" --device auto
succeed gpu-auto-nml            -- sweep --config gpu_auto.nml --quiet --output a.h5
succeed gpu-auto-lyapunov       -- "${G[@]}" --device auto --lyapunov
succeed gpu-cpu-explicit        -- "${G[@]}" --device CPU --gpu-repack 0
