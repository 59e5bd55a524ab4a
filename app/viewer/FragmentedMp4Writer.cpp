#include "app/viewer/FragmentedMp4Writer.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

std::string describe(int averror) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(averror, text, sizeof text);
  return text;
}

}  // namespace

struct FragmentedMp4Writer::Impl {
  std::string where;
  cv::Size size, encoded;  // frames given, frames encoded (even sides)
  cv::Mat padded;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* convert = nullptr;
  std::int64_t nextPts = 0;
  bool headerWritten = false, finished = false;

  ~Impl() {
    if (format && headerWritten && !finished) av_write_trailer(format);
    if (format && format->pb) avio_closep(&format->pb);
    sws_freeContext(convert);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    avformat_free_context(format);
  }

  [[noreturn]] void fail(const std::string& what, int averror) const {
    throw Error(where + ": " + what + " (" + describe(averror) + ")");
  }

  // Sends `input` (nullptr: end of stream) and writes every packet the encoder returns.
  void encode(const AVFrame* input) {
    if (const int r = avcodec_send_frame(codec, input); r < 0)
      fail("the encoder refused a frame", r);
    for (;;) {
      const int r = avcodec_receive_packet(codec, packet);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("the encoder failed", r);
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = av_interleaved_write_frame(format, packet);  // takes the packet's data
      if (w < 0) fail("cannot write the video (is the disk full or a file-size limit reached?)", w);
    }
  }
};

FragmentedMp4Writer::FragmentedMp4Writer(const std::filesystem::path& path, double fps,
                                         cv::Size size)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.where = "video '" + path.string() + "'";
  m.size = size;
  if (size.width <= 0 || size.height <= 0) throw Error(m.where + ": empty frame size");
  m.encoded = {size.width + size.width % 2, size.height + size.height % 2};
  if (!(std::isfinite(fps) && fps > 0)) throw Error(m.where + ": frame rate must be positive");
  if (const int r = avformat_alloc_output_context2(&m.format, nullptr, "mp4", path.c_str()); r < 0)
    m.fail("the MP4 muxer cannot be created", r);
  const AVCodec* encoder = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (!encoder) throw Error(m.where + ": FFmpeg has no MPEG-4 encoder");
  m.stream = avformat_new_stream(m.format, nullptr);
  m.codec = avcodec_alloc_context3(encoder);
  m.frame = av_frame_alloc();
  m.packet = av_packet_alloc();
  if (!m.stream || !m.codec || !m.frame || !m.packet) throw Error(m.where + ": out of memory");
  const AVRational rate = av_d2q(fps, 100000);
  m.codec->width = m.encoded.width;
  m.codec->height = m.encoded.height;
  m.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  m.codec->time_base = av_inv_q(rate);
  m.codec->framerate = rate;
  m.codec->gop_size = std::max(1, static_cast<int>(std::lround(fps)));  // a fragment per second
  // Constant quantiser 3 (of 1-31): overlays' thin lines stay crisp, about 0.1 bit per pixel.
  m.codec->flags |= AV_CODEC_FLAG_QSCALE;
  m.codec->global_quality = FF_QP2LAMBDA * 3;
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (const int r = avcodec_open2(m.codec, encoder, nullptr); r < 0)
    m.fail("the MPEG-4 encoder cannot be opened", r);
  if (const int r = avcodec_parameters_from_context(m.stream->codecpar, m.codec); r < 0)
    m.fail("the stream cannot be set up", r);
  m.stream->time_base = m.codec->time_base;
  m.stream->avg_frame_rate = rate;
  if (const int r = avio_open(&m.format->pb, path.c_str(), AVIO_FLAG_WRITE); r < 0)
    m.fail("cannot be created (is the folder writable?)", r);
  AVDictionary* options = nullptr;
  // No index held until the end: a moof+mdat fragment per key frame, the moov up front.
  av_dict_set(&options, "movflags", "frag_keyframe+empty_moov+default_base_moof", 0);
  const int header = avformat_write_header(m.format, &options);
  av_dict_free(&options);
  if (header < 0) m.fail("cannot write the MP4 header", header);
  m.headerWritten = true;
  m.frame->format = m.codec->pix_fmt;
  m.frame->width = m.encoded.width;
  m.frame->height = m.encoded.height;
  if (const int r = av_frame_get_buffer(m.frame, 0); r < 0) m.fail("out of memory", r);
  m.convert =
      sws_getContext(m.encoded.width, m.encoded.height, AV_PIX_FMT_BGR24, m.encoded.width,
                     m.encoded.height, AV_PIX_FMT_YUV420P, SWS_POINT, nullptr, nullptr, nullptr);
  if (!m.convert) throw Error(m.where + ": no BGR to YUV 4:2:0 conversion");
}

FragmentedMp4Writer::~FragmentedMp4Writer() = default;

void FragmentedMp4Writer::write(const cv::Mat& bgr) {
  Impl& m = *impl_;
  if (m.finished) throw Error(m.where + " is already finished");
  if (bgr.size() != m.size || bgr.type() != CV_8UC3)
    throw Error(m.where + ": a frame is " + std::to_string(bgr.cols) + "x" +
                std::to_string(bgr.rows) + " but the video is " + std::to_string(m.size.width) +
                "x" + std::to_string(m.size.height) + " BGR");
  if (const int r = av_frame_make_writable(m.frame); r < 0) m.fail("out of memory", r);
  const cv::Mat* image = &bgr;
  if (m.encoded != m.size) {
    cv::copyMakeBorder(bgr, m.padded, 0, m.encoded.height - m.size.height, 0,
                       m.encoded.width - m.size.width, cv::BORDER_REPLICATE);
    image = &m.padded;
  }
  const std::uint8_t* source[1] = {image->data};
  const int sourceStride[1] = {static_cast<int>(image->step[0])};
  sws_scale(m.convert, source, sourceStride, 0, image->rows, m.frame->data, m.frame->linesize);
  m.frame->pts = m.nextPts++;
  m.encode(m.frame);
}

void FragmentedMp4Writer::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  m.finished = true;  // even when the end fails: the destructor must not write a second trailer
  m.encode(nullptr);
  if (const int r = av_write_trailer(m.format); r < 0) m.fail("cannot finish the MP4", r);
  if (const int r = avio_closep(&m.format->pb); r < 0) m.fail("cannot close the MP4", r);
}

}  // namespace reftrack::app
