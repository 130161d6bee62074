# dpend animate: bad frame rates, sizes, speeds and durations, the frame
# cap, missing or non-simulate inputs and overlays, an existing GIF without --force,
# device outputs, a missing --frames directory or existing frames; names with
# quotes and blanks work. Refused input: one line naming the field, exit 2, nothing
# created. Successful rows are tiny (a few 64x64 frames of existing.h5, t_end 0.1 s).

(
  cd "$FIXTURES" &&
  "$DPEND" simulate --t-end 1 --output sim1.h5 &&
  cp existing.h5 "it's \"q\" a.h5" &&
  printf 'GIF89a' > existing.gif &&
  mkdir framedir "fr'a \"m\" \$(b)" && printf 'x' > framedir/frame_0001.png
) > /dev/null 2>&1 || echo "animate.sh: could not make the fixtures" >&2
# a figure within 1e-310 m of the origin (fuzz seed 20261130 case 2239: the arrow
# scale, N per m of the reach, overflowed; SIGFPE in the debug build)
( cd "$FIXTURES" && "$(dirname "$DPEND")/../example/dpend-fuzz-h5" sim1.h5 tiny_figure.h5 \
    fill /trajectory/rJ 1e-310 ) > /dev/null 2>&1 ||
  echo "animate.sh: could not make tiny_figure.h5 (dpend-fuzz-h5 beside the binary)" >&2

A=(animate existing.h5 --output a.gif)
T=(--fps 5 --size 64x64)   # tiny successful runs

refuse  ani-fps-zero       fps      -- "${A[@]}" --fps 0
refuse  ani-figure-at-origin 'points all lie' -- animate tiny_figure.h5 --output t.gif --reactions "${T[@]}"
refuse  ani-fps-big        fps      -- "${A[@]}" --fps 101
refuse  ani-fps-real       fps      -- "${A[@]}" --fps 2.5
refuse  ani-fps-nan        fps      -- "${A[@]}" --fps nan
refuse  ani-fps-missing    fps      -- "${A[@]}" --fps
refuse  ani-size-small     size     -- "${A[@]}" --size 63x64
refuse  ani-size-big       size     -- "${A[@]}" --size 640x4097
refuse  ani-size-huge      size     -- "${A[@]}" --size 99999999999x640
refuse  ani-size-one       size     -- "${A[@]}" --size 640
refuse  ani-size-neg       size     -- "${A[@]}" --size -640x640
refuse  ani-size-junk      size     -- "${A[@]}" --size 640x64a
refuse  ani-speed-zero     speed    -- "${A[@]}" --speed 0
refuse  ani-speed-neg      speed    -- "${A[@]}" --speed -1
refuse  ani-speed-nan      speed    -- "${A[@]}" --speed nan
refuse  ani-speed-big      speed    -- "${A[@]}" --speed 1e4
refuse  ani-dur-zero       duration -- "${A[@]}" --duration 0
refuse  ani-dur-neg        duration -- "${A[@]}" --duration -1
refuse  ani-dur-inf        duration -- "${A[@]}" --duration inf
refuse  ani-dur-huge       duration -- "${A[@]}" --duration 1e300
refuse  ani-dur-past-end   duration -- "${A[@]}" --duration 1
refuse  ani-dur-cap        duration -- animate sim1.h5 --output a.gif --duration 500 --fps 100
refuse  ani-whole-cap      duration -- animate sim1.h5 --output a.gif --speed 0.001 --fps 100
refuse  ani-no-input       input    -- animate --fps 5
refuse  ani-missing        input    -- animate nowhere.h5 --output a.gif
refuse  ani-directory      input    -- animate dir --output a.gif
refuse  ani-not-hdf5       input    -- animate list.txt --output a.gif
refuse  ani-sweep-file     input    -- animate sweep.h5 --output a.gif
refuse  ani-two-inputs     argument -- animate existing.h5 sim1.h5 --output a.gif
refuse  ani-unknown        option   -- "${A[@]}" --bogus 1
refuse  ani-force-value    force    -- "${A[@]}" --force=yes
refuse  ani-exists         output   -- animate sim1.h5 --output existing.gif "${T[@]}"
refuse  ani-default-exists output   -- animate existing.h5 "${T[@]}"
refuse  ani-device         output   -- "${A[@]}" --output /dev/null "${T[@]}"
refuse  ani-device-force   output   -- "${A[@]}" --output /dev/null --force "${T[@]}"
refuse  ani-out-dir        output   -- "${A[@]}" --output dir "${T[@]}"
refuse  ani-out-nodir      output   -- "${A[@]}" --output nodir/a.gif "${T[@]}"
refuse  ani-overlay-none   overlay  -- "${A[@]}" --overlay nowhere.h5 "${T[@]}"
refuse  ani-overlay-sweep  overlay  -- "${A[@]}" --overlay sweep.h5 "${T[@]}"
refuse  ani-overlay-short  duration -- animate sim1.h5 --output a.gif --overlay existing.h5 \
                                       --duration 1 "${T[@]}"
refuse  ani-frames-nodir   frames   -- "${A[@]}" --frames nodir "${T[@]}"
refuse  ani-frames-file    frames   -- "${A[@]}" --frames list.txt "${T[@]}"
refuse  ani-frames-exist   frames   -- "${A[@]}" --frames framedir "${T[@]}"

succeed ani-tiny                    -- "${A[@]}" "${T[@]}"
succeed ani-quotes-input            -- animate "it's \"q\" a.h5" "${T[@]}"
succeed ani-quotes-output           -- animate existing.h5 --output "o'k \"x\" \$(y).gif" "${T[@]}"
succeed ani-quotes-overlay          -- "${A[@]}" --overlay "it's \"q\" a.h5" --reactions "${T[@]}"
succeed ani-force                   -- animate sim1.h5 --output existing.gif --force \
                                       --duration 0.4 "${T[@]}"
succeed ani-frames-force            -- "${A[@]}" --frames framedir --force --duration 0.2 \
                                       "${T[@]}"
succeed ani-frames-quotes           -- "${A[@]}" --frames "fr'a \"m\" \$(b)" --speed 0.25 \
                                       --duration 0.4 \
                                       --size 64x96
