#include "app/simulator/VideoCodecRoundTrip.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/log.h>
}

#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

std::string describe(int averror) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(averror, text, sizeof text);
  return text;
}

EncodedVideo roundTripJpeg(const std::vector<cv::Mat>& frames, int quality) {
  EncodedVideo out;
  std::vector<uchar> buffer;
  for (const cv::Mat& frame : frames) {
    if (!cv::imencode(".jpg", frame, buffer, {cv::IMWRITE_JPEG_QUALITY, quality}))
      throw Error("mjpeg: cannot encode a frame");
    out.bytes += buffer.size();
    cv::Mat decoded = cv::imdecode(buffer, cv::IMREAD_COLOR);
    if (decoded.empty()) throw Error("mjpeg: cannot decode a frame");
    out.frames.push_back(decoded);
  }
  return out;
}

// I420 (Y, then U, then V, each plane's rows contiguous: cv::COLOR_BGR2YUV_I420's layout) and an
// AVFrame's YUV 4:2:0 planes (rows `linesize` apart), both ways.
void copyPlanes(const cv::Mat& i420, AVFrame* frame) {
  const int w = frame->width, h = frame->height;
  const std::uint8_t* source = i420.data;
  for (int plane = 0; plane < 3; ++plane) {
    const int pw = plane == 0 ? w : w / 2, ph = plane == 0 ? h : h / 2;
    for (int y = 0; y < ph; ++y, source += pw)
      std::memcpy(frame->data[plane] + static_cast<std::ptrdiff_t>(y) * frame->linesize[plane],
                  source, static_cast<std::size_t>(pw));
  }
}

cv::Mat i420Of(const AVFrame* frame) {
  const int w = frame->width, h = frame->height;
  cv::Mat i420(h * 3 / 2, w, CV_8U);
  std::uint8_t* target = i420.data;
  for (int plane = 0; plane < 3; ++plane) {
    const int pw = plane == 0 ? w : w / 2, ph = plane == 0 ? h : h / 2;
    for (int y = 0; y < ph; ++y, target += pw)
      std::memcpy(target,
                  frame->data[plane] + static_cast<std::ptrdiff_t>(y) * frame->linesize[plane],
                  static_cast<std::size_t>(pw));
  }
  return i420;
}

// One encoder and decoder, freed however the round trip ends. The colour conversions are
// OpenCV's (BT.601 video range, as FFmpeg's; fixed-point, the same on any CPU).
struct CodecPair {
  std::string codec;
  AVCodecContext* encoder = nullptr;
  AVCodecContext* decoder = nullptr;
  AVFrame* yuv = nullptr;
  AVFrame* decoded = nullptr;
  AVPacket* packet = nullptr;
  cv::Size size, encoded;  // frames given; encoded (even sides, as 4:2:0 needs)
  EncodedVideo out;

  ~CodecPair() {
    av_packet_free(&packet);
    av_frame_free(&decoded);
    av_frame_free(&yuv);
    avcodec_free_context(&decoder);
    avcodec_free_context(&encoder);
  }

  [[noreturn]] void fail(const std::string& what, int averror) const {
    throw Error("video codec '" + codec + "': " + what + " (" + describe(averror) + ")");
  }

  void open(double fps) {
    const bool h264 = codec == "h264";
    const AVCodec* enc =
        h264 ? avcodec_find_encoder_by_name("libx264") : avcodec_find_encoder(AV_CODEC_ID_MPEG4);
    const AVCodec* dec = avcodec_find_decoder(h264 ? AV_CODEC_ID_H264 : AV_CODEC_ID_MPEG4);
    if (!enc || !dec) throw Error("video codec '" + codec + "' is not available in FFmpeg");
    encoder = avcodec_alloc_context3(enc);
    decoder = avcodec_alloc_context3(dec);
    yuv = av_frame_alloc();
    decoded = av_frame_alloc();
    packet = av_packet_alloc();
    if (!encoder || !decoder || !yuv || !decoded || !packet)
      throw Error("video codec '" + codec + "': out of memory");
    const AVRational rate = av_d2q(fps, 100000);
    encoder->width = encoded.width;
    encoder->height = encoded.height;
    encoder->pix_fmt = AV_PIX_FMT_YUV420P;
    encoder->time_base = av_inv_q(rate);
    encoder->framerate = rate;
    // Fixed settings, so the stream and the frames decoded from it are the same on any machine:
    // one thread each way (FFmpeg's default is one per core), and code that does not depend on
    // the CPU. x264 picks its SIMD code by CPU, and its levels are not bit-exact with each other
    // (AVX2, SSE2 and plain C gave three different streams of the same frames); its AVX-512 code
    // is not even repeatable (4 different streams in 40 encodes of the same 5 frames, one thread,
    // on an AMD EPYC (Zen 4): the cause of issue 25's failure). SSE2, which every x86-64 CPU has,
    // gave one stream in 40 and costs ~10% over AVX2.
    encoder->thread_count = 1;
    decoder->thread_count = 1;
    encoder->flags |= AV_CODEC_FLAG_BITEXACT;
    decoder->flags |= AV_CODEC_FLAG_BITEXACT;
    AVDictionary* options = nullptr;
    if (h264) {
      // What OpenCV 4.6's writer gave before: x264's defaults, constant quality 23.
      av_dict_set(&options, "preset", "medium", 0);
      av_dict_set(&options, "crf", "23", 0);
#if defined(__x86_64__) || defined(__i386__)
      av_dict_set(&options, "x264-params", "asm=SSE2", 0);
#endif
    } else {
      // What OpenCV 4.6's writer gave: width x height x fps bit/s, a key frame every 12 frames,
      // no B-frames (MPEG-4 Simple Profile). The integer DCT and the simple IDCT in C: FFmpeg
      // would pick SIMD versions by CPU.
      encoder->bit_rate = static_cast<std::int64_t>(encoded.area() * fps);
      encoder->gop_size = 12;
      encoder->max_b_frames = 0;
      encoder->dct_algo = FF_DCT_INT;
      encoder->idct_algo = FF_IDCT_SIMPLE;
      decoder->idct_algo = FF_IDCT_SIMPLE;
    }
    const int opened = avcodec_open2(encoder, enc, &options);
    av_dict_free(&options);
    if (opened < 0) fail("the encoder cannot be opened", opened);
    if (const int r = avcodec_open2(decoder, dec, nullptr); r < 0)
      fail("the decoder cannot be opened", r);
    yuv->format = AV_PIX_FMT_YUV420P;
    yuv->width = encoded.width;
    yuv->height = encoded.height;
    if (const int r = av_frame_get_buffer(yuv, 0); r < 0) fail("out of memory", r);
    for (AVBufferRef* buffer : yuv->buf)  // the rows' padding too: nothing left unset
      if (buffer) std::memset(buffer->data, 0, buffer->size);
  }

  // `bgr` (of the encoded size) into the encoder as frame `index`.
  void send(const cv::Mat& bgr, std::int64_t index) {
    cv::Mat i420;
    cv::cvtColor(bgr, i420, cv::COLOR_BGR2YUV_I420);
    if (const int r = av_frame_make_writable(yuv); r < 0) fail("out of memory", r);
    copyPlanes(i420, yuv);
    yuv->pts = index;
    encode(yuv);
  }

  // Sends `input` (nullptr: the end) and decodes every packet the encoder returns.
  void encode(const AVFrame* input) {
    if (const int r = avcodec_send_frame(encoder, input); r < 0)
      fail("the encoder refused a frame", r);
    for (;;) {
      const int r = avcodec_receive_packet(encoder, packet);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) break;
      if (r < 0) fail("the encoder failed", r);
      out.bytes += static_cast<std::size_t>(packet->size);
      const int sent = avcodec_send_packet(decoder, packet);
      av_packet_unref(packet);
      if (sent < 0) fail("the decoder refused a packet", sent);
      receiveDecoded();
    }
    if (!input) {
      if (const int r = avcodec_send_packet(decoder, nullptr); r < 0)
        fail("the decoder cannot be flushed", r);
      receiveDecoded();
    }
  }

  void receiveDecoded() {
    for (;;) {
      const int r = avcodec_receive_frame(decoder, decoded);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("the decoder failed", r);
      if (decoded->width != encoded.width || decoded->height != encoded.height ||
          decoded->format != AV_PIX_FMT_YUV420P)
        throw Error("video codec '" + codec + "': a decoded frame is not " +
                    std::to_string(encoded.width) + "x" + std::to_string(encoded.height) +
                    " YUV 4:2:0");
      cv::Mat bgr;
      cv::cvtColor(i420Of(decoded), bgr, cv::COLOR_YUV2BGR_I420);
      av_frame_unref(decoded);
      out.frames.push_back(encoded == size ? bgr : bgr(cv::Rect({0, 0}, size)).clone());
    }
  }
};

}  // namespace

EncodedVideo roundTripVideo(const std::vector<cv::Mat>& frames, const std::string& codec,
                            double fps, int jpegQuality) {
  if (frames.empty()) return {};
  // FFmpeg's messages below errors (x264's statistics on closing) stay off the terminal, as
  // OpenCV's FFmpeg backend keeps them.
  if (av_log_get_level() > AV_LOG_ERROR) av_log_set_level(AV_LOG_ERROR);
  for (const cv::Mat& f : frames)
    if (f.type() != CV_8UC3 || f.size() != frames.front().size())
      throw Error("video codec: frames must be CV_8UC3 and all of one size");
  if (codec == "mjpeg") return roundTripJpeg(frames, jpegQuality);
  if (codec != "h264" && codec != "mp4v")
    throw Error("video codec '" + codec + "' is unknown (h264, mp4v, mjpeg)");
  if (!(fps > 0.0)) throw Error("video codec '" + codec + "': the frame rate must be positive");
  CodecPair pair;
  pair.codec = codec;
  pair.size = frames.front().size();
  pair.encoded = {pair.size.width + pair.size.width % 2, pair.size.height + pair.size.height % 2};
  pair.open(fps);
  cv::Mat padded;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const cv::Mat* image = &frames[k];
    if (pair.encoded != pair.size) {
      cv::copyMakeBorder(frames[k], padded, 0, pair.encoded.height - pair.size.height, 0,
                         pair.encoded.width - pair.size.width, cv::BORDER_REPLICATE);
      image = &padded;
    }
    pair.send(*image, static_cast<std::int64_t>(k));
  }
  pair.encode(nullptr);
  if (pair.out.frames.size() != frames.size())
    throw Error("video codec '" + codec + "': decoded " + std::to_string(pair.out.frames.size()) +
                " of " + std::to_string(frames.size()) + " frames");
  return std::move(pair.out);
}

}  // namespace reftrack::app
